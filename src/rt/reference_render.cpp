#include "rt/reference_render.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/interrupt.h"
#include "core/parallel.h"
#include "core/profiler.h"
#include "shading/surface_resolve.h"

namespace tandem {

void SampleSums::reset(int w, int h) {
  width = w;
  height = h;
  samples = 0;
  data.assign(size_t(w) * size_t(h) * 4, 0.0);
}

void SampleSums::resolve(Buffer& hdr, Buffer* variance) const {
  const double n = std::max(samples, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double* p = &data[(size_t(y) * size_t(width) + size_t(x)) * 4];
      const Vec3 mean(float(p[0] / n), float(p[1] / n), float(p[2] / n));
      hdr.setRgb(x, y, mean);
      if (variance) {
        const double m = luminance(mean);
        const double var = samples > 1 ? std::max(p[3] / n - m * m, 0.0) / (n - 1.0) : 0.0;
        variance->at(x, y)[0] = float(var);
      }
    }
}

double SampleSums::relativeError() const {
  if (samples < 2 || data.empty()) return 0.0;
  Buffer hdr(width, height, 3), variance(width, height, 1);
  resolve(hdr, &variance);
  return relativeNoise(hdr, variance);
}

double relativeNoise(const Buffer& hdr, const Buffer& variance) {
  // The median pixel's standard error relative to its value (values under 1/1000 of the image
  // mean count as that floor, so black pixels do not read as infinitely noisy). The median
  // says how noisy the image looks; an RMS would follow the few firefly pixels.
  double mean = 0;
  for (int y = 0; y < hdr.height; ++y)
    for (int x = 0; x < hdr.width; ++x) mean += luminance(hdr.rgb(x, y));
  mean /= double(std::max<size_t>(hdr.pixelCount(), 1));
  if (!(mean > 0)) return 0.0;
  std::vector<double> rel;
  rel.reserve(hdr.pixelCount());
  for (int y = 0; y < hdr.height; ++y)
    for (int x = 0; x < hdr.width; ++x)
      rel.push_back(std::sqrt(double(variance.at(x, y)[0])) /
                    std::max(double(luminance(hdr.rgb(x, y))), 1e-3 * mean));
  std::nth_element(rel.begin(), rel.begin() + long(rel.size() / 2), rel.end());
  return rel[rel.size() / 2];
}

Camera cameraAtShutter(const Camera& open, const Camera& close, float tau) {
  CameraDesc d = open.desc;
  d.position = lerp(open.desc.position, close.desc.position, tau);
  d.lookAt = lerp(open.desc.lookAt, close.desc.lookAt, tau);
  return Camera::make(d, open.width, open.height, open.jitter);
}

namespace {

void drawProgress(int done, int target, double seconds, double relErr, bool final) {
  const int width = 30, filled = target > 0 ? int(double(width) * done / target) : width;
  const double eta = done > 0 ? seconds * double(target - done) / double(done) : 0.0;
  std::fprintf(stderr, "\r[%-*.*s] %5d/%d spp  %6.1f s  ETA %6.1f s  noise %.2f %%  ", width,
               std::min(filled, width), "##############################", done, target, seconds,
               eta, 100.0 * relErr);
  if (final) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace

ReferenceResult renderReference(const RayTracer& rt, const Scene& scene, const Camera& open,
                                const Camera& close, const ReferenceSettings& settings,
                                SampleCluster& cluster, SampleSums& sums) {
  const int width = open.width, height = open.height;
  if (sums.width != width || sums.height != height || sums.data.empty()) sums.reset(width, height);
  const ShadingContext shading = ShadingContext::from(scene);
  PathTracer pt(rt, scene, shading, settings.path);
  const Whitted whitted(rt, scene, shading, settings.whitted);
  const bool drt = settings.integrator == Integrator::Whitted;
  const bool diffuseGI = settings.integrator == Integrator::DiffuseGI;
  // The reference picks lights by the grid: the same expectation as uniform selection, less noise.
  const LightGrid grid = diffuseGI ? DiffuseGI::buildGrid(scene, shading, &rt)
                                   : LightGrid(shading.lights, {}, Bounds3{});
  const DiffuseGI gi(rt, scene, shading, &grid);
  // The foveated path tracer's estimate at the surface its G-buffer holds: pixel centre, no lens,
  // the primary hit's texture level of detail as rt_gbuffer filters it.
  auto diffuseGIRadiance = [&](const Camera& cam, float px, float py, SobolSampler& rng) {
    Vec3 o, d;
    cam.generateRay(px, py, o, d);
    Ray r;
    r.origin = o;
    r.dir = d;
    r.tnear = cam.desc.projection == Projection::Perspective
                  ? cam.desc.nearPlane / std::max(dot(d, cam.forward), 1e-6f)
                  : cam.desc.nearPlane;
    const Hit h = rt.intersect(r, /*cullBackfaces=*/true);
    if (!h.valid()) return scene.skyRadiance(d);
    const float tuv[3] = {h.t, h.u, h.v};
    const SurfaceSample s =
        resolveSurface(*rt.frame(), h.object, h.prim, o, d, 0.0f, tuv, pixelSpreadAngle(cam));
    uint64_t rays = 0;
    return gi.radiance(s, -d, rng, 0.0f, rays);
  };
  // Distributed ray tracing of the hybrids' shading: the camera ray starts at the near plane
  // and culls back faces as the rasterizer does, then Whitted shading of the hit.
  auto whittedRadiance = [&](const Camera& cam, Vec3 o, Vec3 d, float tau) {
    Ray r;
    r.origin = o;
    r.dir = d;
    r.tnear = cam.desc.nearPlane / std::max(dot(d, cam.forward), 1e-6f);
    r.time = tau;
    const Hit h = rt.intersect(r, /*cullBackfaces=*/true);
    if (!h.valid()) return scene.skyRadiance(d);
    const float tuv[3] = {h.t, h.u, h.v};
    const SurfaceSample s = resolveSurface(*rt.frame(), h.object, h.prim, o, d, tau, tuv);
    return tau > 0.0f ? whitted.atTime(tau).shadePrimary(s, d) : whitted.shadePrimary(s, d);
  };
  const bool cameraMoves = std::memcmp(&open.desc.position, &close.desc.position, sizeof(Vec3)) ||
                           std::memcmp(&open.desc.lookAt, &close.desc.lookAt, sizeof(Vec3));
  const bool progress = settings.progress && cluster.rank() == 0 && isatty(STDERR_FILENO);
  const uint64_t raysBefore = rt.raysTraced();
  const auto start = Clock::now();
  ReferenceResult result;
  while (sums.samples < settings.spp) {
    pollInterrupt();  // between batches: the sums hold whole samples
    // Batches double (1, 1, 2, 4, ... 64) so the first image and estimate come quickly; with a
    // time limit the batch shrinks to what the measured rate says still fits.
    int batch = std::min({settings.spp - sums.samples, std::max(sums.samples, 1), 64});
    if (settings.timeLimitS > 0 && sums.samples > 0) {
      const double perSample = msSince(start) * 1e-3 / double(sums.samples);
      const double left = settings.timeLimitS - msSince(start) * 1e-3;
      batch = std::min(batch, int(std::floor(left / std::max(perSample, 1e-9))));
    }
    batch = cluster.broadcast(std::max(batch, 0));
    if (batch <= 0) break;
    const int first = sums.samples;
    parallelTiles(width, height, [&](int x0, int y0, int x1, int y1) {
      for (int y = y0; y < y1; ++y) {
        if (!cluster.ownsRow(y)) continue;
        for (int x = x0; x < x1; ++x) {
          double* acc = &sums.data[(size_t(y) * size_t(width) + size_t(x)) * 4];
          const uint64_t pixel = uint64_t(y) * uint64_t(width) + uint64_t(x);
          for (int i = first; i < first + batch; ++i) {
            SobolSampler sampler(settings.seed, pixel, uint32_t(i));
            const Vec2 jitter = sampler.get2D(), lens = sampler.get2D();
            const float tau = sampler.uniform();  // shutter time
            auto sample = [&](const Camera& c) {
              Vec3 o, d;
              c.generateThinLensRay(x + jitter.x, y + jitter.y, lens.x, lens.y, o, d);
              return drt ? whittedRadiance(c, o, d, tau) : pt.radiance(o, d, tau, sampler);
            };
            Vec3 L = diffuseGI     ? diffuseGIRadiance(open, x + 0.5f, y + 0.5f, sampler)
                     : cameraMoves ? sample(cameraAtShutter(open, close, tau))
                                   : sample(open);
            // A NaN or infinite sample (a degenerate pdf) must not poison the pixel.
            if (!(std::isfinite(L.x) && std::isfinite(L.y) && std::isfinite(L.z))) L = Vec3(0.0f);
            const double lum = luminance(L);
            acc[0] += L.x;
            acc[1] += L.y;
            acc[2] += L.z;
            acc[3] += lum * lum;
          }
        }
      }
    });
    sums.samples += batch;
    if (progress)
      drawProgress(sums.samples, settings.spp, msSince(start) * 1e-3, sums.relativeError(), false);
  }
  result.seconds = msSince(start) * 1e-3;
  if (progress)
    drawProgress(sums.samples, settings.spp, result.seconds, sums.relativeError(), true);
  cluster.reduceSum(sums.data);
  std::vector<double> rays{double(rt.raysTraced() - raysBefore)};
  cluster.reduceSum(rays);  // every process's rays, on rank 0
  result.spp = sums.samples;
  result.rays = uint64_t(rays[0]);
  if (cluster.rank() == 0) result.relativeError = sums.relativeError();
  return result;
}

}  // namespace tandem
