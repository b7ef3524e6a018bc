// Google Benchmark micro-benchmarks of the hot loops (build with -DTANDEM_BENCH=ON).
#include <benchmark/benchmark.h>

#include "core/parallel.h"
#include "eval/metrics.h"
#include "raster/rasterizer.h"
#include "rt/ray_tracer.h"
#include "scene/builtin_scenes.h"

using namespace tandem;

namespace {
const Scene& atrium() {
  static const Scene s = makeAtriumScene();
  return s;
}
}  // namespace

// The rasterizer's visibility stage alone (no attribute resolve), atrium at 1280x720.
static void BM_RasterVisibilityAtrium(benchmark::State& state) {
  FrameScene fs;
  fs.update(atrium(), 0, 0);
  Camera cam = Camera::make(atrium().camera, 1280, 720);
  Rasterizer r;
  VisibilityBuffer vb;
  for (auto _ : state) {
    r.render(fs, cam, vb);
    benchmark::DoNotOptimize(vb.depth.data());
  }
}
BENCHMARK(BM_RasterVisibilityAtrium)->Unit(benchmark::kMillisecond)->UseRealTime();

// Primary rays alone (8-wide packets), atrium at 1280x720: the ray-traced visibility stage.
static void BM_PrimaryRaysAtrium(benchmark::State& state) {
  FrameScene fs;
  fs.update(atrium(), 0, 0);
  Camera cam = Camera::make(atrium().camera, 1280, 720);
  RayTracer rt;
  rt.update(fs);
  for (auto _ : state) {
    // Same tiling and packet shape as the rt_gbuffer pass, on all threads like the rasterizer.
    parallelTiles(1280, 720, [&](int x0, int y0, int x1, int y1) {
      for (int y = y0; y < y1; y += 2)
        for (int x = x0; x < x1; x += 4) {
          Ray rays[8];
          Hit hits[8];
          for (int k = 0; k < 8; ++k)
            cam.generateRay(x + (k & 3) + 0.5f, y + (k >> 2) + 0.5f, rays[k].origin, rays[k].dir);
          rt.intersect8(rays, 8, hits, true);
          benchmark::DoNotOptimize(hits);
        }
    });
  }
  state.counters["Mrays/s"] = benchmark::Counter(1280.0 * 720.0 * double(state.iterations()) / 1e6,
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PrimaryRaysAtrium)->Unit(benchmark::kMillisecond)->UseRealTime();

static void BM_Ssim720p(benchmark::State& state) {
  Buffer a(1280, 720, 3), b(1280, 720, 3);
  for (size_t i = 0; i < a.data.size(); ++i) {
    a.data[i] = float(i % 255) / 255.0f;
    b.data[i] = float((i * 7) % 255) / 255.0f;
  }
  for (auto _ : state) benchmark::DoNotOptimize(ssim(a, b));
}
BENCHMARK(BM_Ssim720p)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
