#include "passes/dof/rt_dof.h"

#include <atomic>
#include <cmath>
#include <vector>

#include "core/parallel.h"
#include "passes/common/whitted_settings.h"
#include "passes/dof/dof_common.h"
#include "pipeline/frame_context.h"
#include "rt/sampler.h"
#include "rt/whitted.h"
#include "scene/thin_lens.h"
#include "shading/surface_resolve.h"

namespace tandem {

const ParamTable<RTDofSettings>& RTDofPass::tableFor() const {
  using S = RTDofSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .nest(&S::whitted, whittedTable())
          .add(&S::reuseRaster, {.name = "reuse_raster",
                                 .doc = "hits the sharp image shows take its colour instead of "
                                        "being shaded (beyond the paper)"});
  return table;
}

namespace {

// What a pixel's rays add up to.
struct PixelSums {
  Vec3 nearRgb{0.0f}, farRgb{0.0f}, farPos{0.0f};
  float nearW = 0, farW = 0, nearCoc = 0, farCoc = 0, farPosW = 0;
  int rays = 0;
};

// One frame's lens rays: the cameras, the lens and what every tile reads.
struct LensRays {
  FrameContext& ctx;
  std::vector<Camera> cams;  // one per view, unjittered
  const Buffer& mask;
  const Scene& scene;
  RayTracer& rt;
  const Whitted& whitted;
  ThinLens lens;
  float scale, spread, nearT;
  uint64_t seed;
  const Buffer *sharp, *depth;  // reuse_raster: the sharp image and its depth (else null)

  bool rasterColour(int vi, Vec3 hit, float zHit, Vec3& out) const;
  // An 8-ray packet: rays of consecutive pixels (a pixel's own rays are coherent).
  struct Packet {
    Ray rays[8];
    int owner[8], camOf[8], n = 0;
  };
  void flush(Packet& p, std::vector<PixelSums>& sums, uint64_t& reused) const;
  void traceTile(int x0, int y0, int x1, int y1, std::vector<PixelSums>& sums,
                 uint64_t& reused) const;
};

// Beyond the paper (`reuse_raster`): a lens ray that hits a surface the sharp image shows at the
// hit's projection (the depth there within 1 %) takes the sharp colour from there instead of
// being shaded — only rays that see behind the raster's surfaces (the see-through rims) are
// shaded. Exact for diffuse surfaces; view-dependent terms are the pinhole's, not the lens
// point's (a few centimetres away).
bool LensRays::rasterColour(int vi, Vec3 hit, float zHit, Vec3& out) const {
  const View& v = ctx.views[size_t(vi)];
  if (cams[size_t(vi)].desc.projection != Projection::Perspective) return false;
  Vec2 px;
  if (!cams[size_t(vi)].project(hit, px)) return false;
  const int ix = int(px.x), iy = int(px.y);
  if (px.x < 0 || px.y < 0 || ix >= v.width() || iy >= v.height()) return false;
  const float d = depth->at(ix + v.x, iy + v.y)[0];
  if (d <= 0) return false;
  const float zRaster = cams[size_t(vi)].desc.nearPlane / d;  // reversed-Z: near / z
  if (std::abs(zRaster - zHit) > 0.01f * zHit) return false;
  out = sharp->rgb(ix + v.x, iy + v.y);
  return true;
}

void LensRays::flush(Packet& pk, std::vector<PixelSums>& sums, uint64_t& reused) const {
  const int n = pk.n;
  if (n == 0) return;
  const Ray* rays = pk.rays;
  Hit hits[8];
  rt.intersect8(pk.rays, n, hits, /*cullBackfaces=*/true);
  SurfaceSample s[8];
  Vec3 d[8], rgb[8];
  int at[8], m = 0;
  float z[8];
  for (int k = 0; k < n; ++k) {
    if (!hits[k].valid()) {
      z[k] = 1e30f;
      rgb[k] = scene.skyRadiance(rays[k].dir);
      continue;
    }
    const Camera& c = cams[size_t(pk.camOf[k])];
    const Vec3 hit = rays[k].origin + rays[k].dir * hits[k].t;
    z[k] = dot(hit - c.eye, c.forward);
    if (sharp && rasterColour(pk.camOf[k], hit, z[k], rgb[k])) {
      ++reused;
      continue;
    }
    const float tuv[3] = {hits[k].t, hits[k].u, hits[k].v};
    s[m] = resolveSurface(ctx.frame, hits[k].object, hits[k].prim, rays[k].origin, rays[k].dir,
                          0.0f, tuv, spread);
    d[m] = rays[k].dir;
    at[m++] = k;
  }
  Vec3 shaded[8];
  whitted.shadePrimary8(s, d, m, shaded);
  for (int j = 0; j < m; ++j) rgb[at[j]] = shaded[j];
  for (int k = 0; k < n; ++k) {
    PixelSums& p = sums[size_t(pk.owner[k])];
    const float c = lens.coc(z[k]), wn = dof::nearShare(c), wf = 1.0f - wn;
    p.nearRgb = p.nearRgb + rgb[k] * wn;
    p.farRgb = p.farRgb + rgb[k] * wf;
    p.nearW += wn;
    p.farW += wf;
    p.nearCoc += wn * std::abs(c);
    p.farCoc += wf * std::min(std::abs(c), 1e6f);
    if (hits[k].valid() && wf > 0) {
      p.farPos = p.farPos + rays[k].origin * wf + rays[k].dir * (hits[k].t * wf);
      p.farPosW += wf;
    }
    ++p.rays;
  }
  pk.n = 0;
}

void LensRays::traceTile(int x0, int y0, int x1, int y1, std::vector<PixelSums>& sums,
                         uint64_t& reused) const {
  const int tw = x1 - x0, w = mask.width;
  Packet pk;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const int count = int(mask.at(x, y)[0]);
      if (count <= 0) continue;
      const uint64_t pixel = uint64_t(y) * uint64_t(w) + uint64_t(x);
      // The view this mask pixel's frame pixels belong to, and the position in it.
      const int fx = std::min(int((float(x) + 0.5f) * scale), ctx.width - 1);
      const int fy = std::min(int((float(y) + 0.5f) * scale), ctx.height - 1);
      const View& view = viewAt(ctx.views, fx, fy);
      const int vi = int(&view - ctx.views.data());
      const Camera& cam = cams[size_t(vi)];
      for (int i = 0; i < count; ++i) {
        SobolSampler sampler(seed, pixel, uint32_t(i));
        const Vec2 j = sampler.get2D(), l = sampler.get2D();
        Ray& r = pk.rays[pk.n];
        cam.generateThinLensRay((float(x) + j.x) * scale - float(view.x),
                                (float(y) + j.y) * scale - float(view.y), l.x, l.y, r.origin,
                                r.dir);
        r.tnear = nearT / std::max(dot(r.dir, cam.forward), 1e-6f);
        pk.camOf[pk.n] = vi;
        r.tfar = 1e30f;
        r.time = 0.0f;
        pk.owner[pk.n] = (y - y0) * tw + (x - x0);
        if (++pk.n == 8) flush(pk, sums, reused);
      }
    }
  flush(pk, sums, reused);
}

// A pixel's sums as the four outputs (dof_common.h: their channels).
void writePixel(const PixelSums& p, int x, int y, Buffer& nearOut, Buffer& farOut, Buffer& hitOut,
                Buffer& farPosOut) {
  const float in = p.nearW > 0 ? 1.0f / p.nearW : 0.0f, inf = p.farW > 0 ? 1.0f / p.farW : 0.0f;
  float* o = nearOut.at(x, y);
  o[0] = p.nearRgb.x * in, o[1] = p.nearRgb.y * in, o[2] = p.nearRgb.z * in;
  o[dof::kLayerCoc] = p.nearCoc * in;
  o = farOut.at(x, y);
  o[0] = p.farRgb.x * inf, o[1] = p.farRgb.y * inf, o[2] = p.farRgb.z * inf;
  o[dof::kLayerCoc] = p.farCoc * inf;
  o = hitOut.at(x, y);
  o[dof::kHitNearShare] = p.rays > 0 ? p.nearW / float(p.rays) : 0.0f;
  o[dof::kHitRays] = float(p.rays);
  o = farPosOut.at(x, y);
  const float ip = p.farPosW > 0 ? 1.0f / p.farPosW : 0.0f;
  o[0] = p.farPos.x * ip, o[1] = p.farPos.y * ip, o[2] = p.farPos.z * ip;
  o[dof::kFarPositionValid] = p.farPosW > 0 ? 1.0f : 0.0f;
}

}  // namespace

std::vector<CounterDesc> RTDofPass::counters() const {
  std::vector<CounterDesc> c = whittedCounters(*this);
  c.insert(c.end(), {
                        {RTDofCounters::lensRays, "lens rays traced (the ray mask summed)"},
                        {RTDofCounters::reusedShare,
                         "share of lens rays that took the sharp image's colour (reuse_raster)"},
                    });
  return c;
}

void RTDofPass::execute(FrameContext& ctx) {
  const Buffer& mask = ctx.input(*this, Slots::rayMask);
  const int w = mask.width, h = mask.height;
  Buffer& nearOut = ctx.output(*this, Slots::rtNear, w, h);
  Buffer& farOut = ctx.output(*this, Slots::rtFar, w, h);
  Buffer& hitOut = ctx.output(*this, Slots::rtHit, w, h);
  Buffer& farPosOut = ctx.output(*this, Slots::rtFarPosition, w, h);
  // Without the TAA jitter: the rays jitter over the pixel themselves, and the accumulation
  // reprojects by motion vectors that carry no jitter, so a jittered view would blur it. One
  // camera per view (stereo: both eyes in one dispatch).
  std::vector<Camera> cams;
  for (const View& v : ctx.views) cams.push_back(v.camera);
  const float scale = float(ctx.width) / float(w);  // frame pixels per mask pixel
  WhittedFrame wf(ctx, *this, settings().whitted);
  const ThinLens lens = ThinLens::of(cams.front());  // the same lens in every view
  const float nearT = cams.front().desc.nearPlane;
  const Buffer* sharp = ctx.optionalInput(*this, Slots::hdr);
  const Buffer* depth = ctx.optionalInput(*this, Slots::depth);
  const bool reuse = settings().reuseRaster && sharp && depth;
  // New lens samples every executed frame (a static shot repeats its frame index).
  const LensRays job{ctx,
                     std::move(cams),
                     mask,
                     *ctx.scene,
                     wf.rt,
                     wf.whitted,
                     lens,
                     scale,
                     ctx.pixelSpread(ctx.views.front()) * scale,
                     nearT,
                     ctx.frameSeed(),
                     reuse ? sharp : nullptr,
                     reuse ? depth : nullptr};
  std::atomic<uint64_t> reusedTotal{0};
  parallelTiles(w, h, [&](int x0, int y0, int x1, int y1) {
    const int tw = x1 - x0;
    uint64_t reused = 0;
    std::vector<PixelSums> sums(size_t(tw) * size_t(y1 - y0));
    job.traceTile(x0, y0, x1, y1, sums, reused);
    reusedTotal += reused;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        writePixel(sums[size_t((y - y0) * tw + (x - x0))], x, y, nearOut, farOut, hitOut,
                   farPosOut);
  });
  wf.finish(ctx, *this, double(w) * double(h));
  double lensRays = 0;
  for (size_t i = 0; i < mask.pixelCount(); ++i) lensRays += mask.data[i];
  ctx.report(*this, RTDofCounters::lensRays, lensRays);
  // Share of lens rays that took the sharp image's colour (reuse_raster) instead of shading.
  ctx.report(*this, RTDofCounters::reusedShare,
             lensRays > 0 ? double(reusedTotal.load()) / lensRays : 0.0);
}

}  // namespace tandem
