#include "passes/dof/rt_dof.h"

#include <atomic>
#include <cmath>
#include <vector>

#include "core/parallel.h"
#include "passes/dof/dof_common.h"
#include "passes/common/whitted_settings.h"
#include "pipeline/frame_context.h"
#include "rt/sampler.h"
#include "rt/whitted.h"
#include "scene/thin_lens.h"
#include "shading/surface_resolve.h"

namespace tandem {

std::vector<ParamDesc> RTDofPass::params() const {
  std::vector<ParamDesc> p = whittedParams();
  p.push_back({"reuse_raster",
               ParamType::Bool,
               0,
               0,
               1,
               "hits the sharp image shows take its colour instead of being shaded (beyond the "
               "paper)",
               {}});
  return p;
}

namespace {

// What a pixel's rays add up to.
struct PixelSums {
  Vec3 nearRgb{0.0f}, farRgb{0.0f}, farPos{0.0f};
  float nearW = 0, farW = 0, nearCoc = 0, farCoc = 0, farPosW = 0;
  int rays = 0;
};

}  // namespace

void RTDofPass::execute(FrameContext& ctx) {
  const Buffer& mask = ctx.input(*this, "ray_mask");
  const int w = mask.width, h = mask.height;
  Buffer& nearOut = ctx.output(*this, "rt_near", w, h);
  Buffer& farOut = ctx.output(*this, "rt_far", w, h);
  Buffer& hitOut = ctx.output(*this, "rt_hit", w, h);
  Buffer& farPosOut = ctx.output(*this, "rt_far_position", w, h);
  // Without the TAA jitter: the rays jitter over the pixel themselves, and the accumulation
  // reprojects by motion vectors that carry no jitter, so a jittered view would blur it. One
  // camera per view (stereo: both eyes in one dispatch).
  std::vector<Camera> cams;
  for (const View& v : ctx.views)
    cams.push_back(Camera::make(v.camera.desc, v.camera.width, v.camera.height));
  const float scale = float(ctx.width) / float(w);  // frame pixels per mask pixel
  RayTracer& rt = ctx.rayTracer();
  const uint64_t before = rt.raysTraced();
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  Whitted whitted(rt, scene, shading, whittedSettings(*this));
  ShadowTally tally;
  prepareShadows(ctx, *this, whitted, &tally);
  const ThinLens lens = ThinLens::of(cams.front());  // the same lens in every view
  const float spread = ctx.pixelSpread(ctx.views.front()) * scale;
  // New lens samples every executed frame (a static shot repeats its frame index).
  const uint64_t seed =
      ctx.seed * 0x9E3779B97F4A7C15ull + uint64_t(ctx.serial) * 0xD1B54A32D192ED03ull;
  const float nearT = cams.front().desc.nearPlane;

  // Beyond the paper (`reuse_raster`): a lens ray that hits a surface the sharp image shows at
  // the hit's projection (the depth there within 1 %) takes the sharp colour from there instead
  // of being shaded — only rays that see behind the raster's surfaces (the see-through rims) are
  // shaded. Exact for diffuse surfaces; view-dependent terms are the pinhole's, not the lens
  // point's (a few centimetres away).
  const Buffer* sharp = ctx.optionalInput(*this, "hdr");
  const Buffer* depth = ctx.optionalInput(*this, "depth");
  const bool reuse = param("reuse_raster") != 0 && sharp && depth;
  auto rasterColour = [&](int vi, Vec3 hit, float zHit, Vec3& out) {
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
  };

  std::atomic<uint64_t> reusedTotal{0};
  parallelTiles(w, h, [&](int x0, int y0, int x1, int y1) {
    const int tw = x1 - x0;
    uint64_t reused = 0;
    std::vector<PixelSums> sums(size_t(tw) * size_t(y1 - y0));
    // An 8-ray packet: rays of consecutive pixels (a pixel's own rays are coherent).
    Ray rays[8];
    int owner[8], camOf[8], n = 0;
    auto flush = [&] {
      if (n == 0) return;
      Hit hits[8];
      rt.intersect8(rays, n, hits, /*cullBackfaces=*/true);
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
        const Camera& c = cams[size_t(camOf[k])];
        const Vec3 hit = rays[k].origin + rays[k].dir * hits[k].t;
        z[k] = dot(hit - c.eye, c.forward);
        if (reuse && rasterColour(camOf[k], hit, z[k], rgb[k])) {
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
        PixelSums& p = sums[size_t(owner[k])];
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
      n = 0;
    };
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
          Ray& r = rays[n];
          cam.generateThinLensRay((float(x) + j.x) * scale - float(view.x),
                                  (float(y) + j.y) * scale - float(view.y), l.x, l.y, r.origin,
                                  r.dir);
          r.tnear = nearT / std::max(dot(r.dir, cam.forward), 1e-6f);
          camOf[n] = vi;
          r.tfar = 1e30f;
          r.time = 0.0f;
          owner[n] = (y - y0) * tw + (x - x0);
          if (++n == 8) flush();
        }
      }
    flush();
    reusedTotal += reused;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const PixelSums& p = sums[size_t((y - y0) * tw + (x - x0))];
        const float in = p.nearW > 0 ? 1.0f / p.nearW : 0.0f,
                    inf = p.farW > 0 ? 1.0f / p.farW : 0.0f;
        float* o = nearOut.at(x, y);
        o[0] = p.nearRgb.x * in, o[1] = p.nearRgb.y * in, o[2] = p.nearRgb.z * in;
        o[3] = p.nearCoc * in;
        o = farOut.at(x, y);
        o[0] = p.farRgb.x * inf, o[1] = p.farRgb.y * inf, o[2] = p.farRgb.z * inf;
        o[3] = p.farCoc * inf;
        o = hitOut.at(x, y);
        o[0] = p.rays > 0 ? p.nearW / float(p.rays) : 0.0f;
        o[1] = float(p.rays);
        o = farPosOut.at(x, y);
        const float ip = p.farPosW > 0 ? 1.0f / p.farPosW : 0.0f;
        o[0] = p.farPos.x * ip, o[1] = p.farPos.y * ip, o[2] = p.farPos.z * ip;
        o[3] = p.farPosW > 0 ? 1.0f : 0.0f;
      }
  });
  reportShadows(ctx, *this, sum(tally), double(w) * double(h));
  ctx.passRays += double(rt.raysTraced() - before);
  double lensRays = 0;
  for (size_t i = 0; i < mask.pixelCount(); ++i) lensRays += mask.data[i];
  ctx.counters["rt_dof/lens_rays"] = lensRays;
  // Share of lens rays that took the sharp image's colour (reuse_raster) instead of shading.
  ctx.counters["rt_dof/reused_share"] = lensRays > 0 ? double(reusedTotal.load()) / lensRays : 0.0;
}

}  // namespace tandem
