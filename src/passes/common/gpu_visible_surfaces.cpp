#include "passes/common/gpu_visible_surfaces.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "gpu/gpu_camera.h"
#include "gpu/shaders/raster_args.h"
#include "gpu/shaders/raster_graphics_args.h"
#include "gpu/shaders/raster_pack_spv.h"
#include "gpu/shaders/raster_queue_spv.h"
#include "gpu/shaders/raster_resolve_spv.h"
#include "gpu/shaders/raster_triangles_f32_spv.h"
#include "gpu/shaders/raster_triangles_spv.h"
#include "passes/common/visible_surfaces.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/gpu_gbuffer.h"
#include "raster/rasterizer.h"

namespace tandem {

namespace {
constexpr uint32_t kQueueGroups = 1024;             // raster_queue's persistent workgroups
constexpr size_t kQueueCapacity = size_t(1) << 18;  // large triangles; the rest drawn directly
constexpr size_t kQueueHeader = 16;                 // the count, padded
}  // namespace

RasterSpans rasterSpans(GpuFrame& gpu, const Scene& scene, const std::vector<uint32_t>& draw) {
  std::vector<RasterSpan> spans;
  RasterSpans out;
  for (size_t o = 0; o < draw.size() && o < scene.objects.size(); ++o) {
    if (!draw[o]) continue;
    const size_t n = scene.meshes[size_t(scene.objects[o].mesh)].triangleCount();
    if (n == 0) continue;
    spans.push_back({uint32_t(out.triangles), uint32_t(o)});
    out.triangles += n;
  }
  out.count = uint32_t(spans.size());
  if (spans.empty()) spans.push_back({0, 0});
  out.address = gpu.constants(spans.data(), spans.size() * sizeof(RasterSpan));
  return out;
}

RasterQueue rasterQueue(GpuFrame& gpu, const std::string& key, size_t triangles) {
  const size_t capacity = std::min(std::max<size_t>(triangles, 1024), kQueueCapacity);
  return {&gpu.scratch(key, kQueueHeader + capacity * sizeof(RasterTriangle)), uint32_t(capacity)};
}

uint64_t recordRasterizer(GpuFrame& gpu, const Scene& scene, uint64_t sceneAddress,
                          const RasterQueue& queue, const RasterView& view) {
  const Camera& cam = *view.camera;
  const RasterSpans spans = rasterSpans(gpu, scene, *view.draw);
  const uint32_t zero[TD_RASTER_COUNT_N] = {};
  RasterArgs a{};
  a.scene = sceneAddress;
  a.spans = spans.address;
  a.spanCount = spans.count;
  a.visibility = view.visibility->address;
  a.queue = queue.buffer->address;
  a.counters = gpu.constants(zero, sizeof zero);
  std::memcpy(a.viewProj, &cam.viewProj.m[0][0], sizeof a.viewProj);
  a.camera = gpuCamera(cam, view.pixelSpread);
  a.triangles = uint32_t(spans.triangles);
  a.objectCount = uint32_t(scene.objects.size());
  a.queueCapacity = queue.capacity;
  a.bothFaces = view.bothFaces ? 1 : 0;
  a.tau = view.tau;
  if (const RasterSamples* r = view.samples) {
    a.sampleStart = r->start;
    a.sampleIds = r->ids;
    a.sampleFixed = r->fixedPos;
    a.samplePos = r->pos;
    a.cellW = r->cellW;
    a.cellH = r->cellH;
    a.cellsX = r->cellsX;
    a.cellsY = r->cellsY;
  }
  const uint64_t args = gpu.constants(&a, sizeof a);
  const GpuKernel& setup = gpu.device().info().float64
                               ? gpu.kernel("raster_triangles", kRasterTrianglesSpv,
                                            sizeof(kRasterTrianglesSpv) / 4, sizeof(uint64_t))
                               : gpu.kernel("raster_triangles_f32", kRasterTrianglesF32Spv,
                                            sizeof(kRasterTrianglesF32Spv) / 4, sizeof(uint64_t));
  const GpuKernel& large =
      gpu.kernel("raster_queue", kRasterQueueSpv, sizeof(kRasterQueueSpv) / 4, sizeof(uint64_t));
  GpuCommands& cmd = gpu.commands();
  cmd.fill(*queue.buffer, 0, kQueueHeader, 0);
  cmd.barrier();
  if (spans.triangles == 0) return a.counters;
  const uint32_t groups = uint32_t((spans.triangles + 63) / 64);
  const uint32_t gx = std::min<uint32_t>(groups, 4096);
  cmd.dispatch(setup, gx, (groups + gx - 1) / gx, 1, &args);
  cmd.barrier();
  cmd.dispatch(large, kQueueGroups, 1, 1, &args);
  cmd.barrier();
  return a.counters;
}

const ParamTable<RasterizerSettings>& rasterizerTable() {
  using S = RasterizerSettings;
  static const ParamTable<S> table = ParamTable<S>().add(
      &S::gpuRasterizer,
      {.name = "gpu_rasterizer",
       .doc = "on the GPU: the compute rasterizer (the CPU's coverage and depths) or the graphics "
              "pipeline (hardware rasterization; edges and depths by the device's rules), to time "
              "one against the other",
       .choices = {"compute", "graphics"}});
  return table;
}

namespace {
// The graphics pipeline's draw of one view into `vis` (its keys, as the compute rasterizer's).
void recordGraphicsVisibility(GpuFrame& gpu, const Scene& scene, uint64_t sceneAddress,
                              const std::string& key, const View& v, const GpuCamera& camera,
                              const std::vector<uint32_t>& draw, const GpuBuffer& vis) {
  const Camera& cam = v.jitteredCamera;
  std::vector<GpuGraphicsRaster::Draw> draws;
  for (size_t o = 0; o < draw.size() && o < scene.objects.size(); ++o) {
    const size_t n = scene.meshes[size_t(scene.objects[o].mesh)].triangleCount();
    if (draw[o] && n > 0) draws.push_back({uint32_t(o), uint32_t(n)});
  }
  const size_t pixels = size_t(cam.width) * size_t(cam.height);
  const GpuBuffer& ids = gpu.scratch(key + "ids", pixels * sizeof(uint32_t));
  const GpuBuffer& depths = gpu.scratch(key + "depths", pixels * sizeof(float));
  RasterDrawArgs d{};
  d.scene = sceneAddress;
  d.camera = gpu.constants(&camera, sizeof camera);
  std::memcpy(d.viewProj, &cam.viewProj.m[0][0], sizeof d.viewProj);
  d.tau = 0;
  GpuCommands& cmd = gpu.commands();
  gpu.graphicsRaster().record(cmd.commandBuffer(), cam.width, cam.height, d, draws, ids, depths);
  RasterPackArgs p{};
  p.ids = ids.address;
  p.depths = depths.address;
  p.visibility = vis.address;
  p.pixels = uint32_t(pixels);
  const uint32_t groups = uint32_t((pixels + 63) / 64), gx = std::min<uint32_t>(groups, 65535);
  cmd.dispatch(
      gpu.kernel("raster_pack", kRasterPackSpv, sizeof(kRasterPackSpv) / 4, sizeof(RasterPackArgs)),
      gx, (groups + gx - 1) / gx, 1, &p);
  cmd.barrier();
}
}  // namespace

void GpuVisibleSurfaces::record(FrameContext& ctx, const Pass& pass, uint64_t targets, uint64_t hdr,
                                const char* resolvePart, bool graphics) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const FrameScene& fs = ctx.frame;
  const Scene& scene = *fs.scene;
  const uint64_t sceneAddress = gpu.scene(fs).sceneAddress();
  const GpuKernel& resolve = gpu.kernel("raster_resolve", kRasterResolveSpv,
                                        sizeof(kRasterResolveSpv) / 4, sizeof(RasterResolveArgs));

  size_t triangleCount = 0;
  for (size_t o = 0; o < fs.objects.size(); ++o)
    triangleCount += scene.meshes[size_t(scene.objects[o].mesh)].triangleCount();
  const std::string key = "raster:" + pass.name() + ":";
  // The compute rasterizer's queue of large triangles (the graphics draw needs none).
  const RasterQueue queueBuffer =
      graphics ? RasterQueue{nullptr, 0} : rasterQueue(gpu, key + "queue", triangleCount);
  const uint64_t motion = gpuObjectMotionConstants(ctx);

  // Counted on the host, as the CPU counts them: every triangle in, those of objects outside
  // the frustum culled; the rest counted by the kernel, per view.
  double in = 0, culledOnHost = 0;
  std::vector<uint64_t> counters;
  const uint32_t t0 = cmd.timestamp();
  std::vector<RasterResolveArgs> resolves;
  for (size_t vi = 0; vi < ctx.views.size(); ++vi) {
    const View& v = ctx.views[vi];
    const Camera& cam = v.jitteredCamera;
    std::vector<uint32_t> draw(std::max<size_t>(fs.objects.size(), 1), 0);
    for (size_t o = 0; o < fs.objects.size(); ++o) {
      draw[o] = boundsOutsideFrustum(cam.viewProj, fs.objects[o].bounds) ? 0 : 1;
      if (!draw[o])
        culledOnHost += double(scene.meshes[size_t(scene.objects[o].mesh)].triangleCount());
    }
    in += double(triangleCount);
    const size_t pixels = size_t(cam.width) * size_t(cam.height);
    const GpuBuffer& vis = gpu.scratch(key + std::to_string(vi), pixels * sizeof(uint64_t));
    if (graphics) {
      recordGraphicsVisibility(gpu, scene, sceneAddress, key + std::to_string(vi) + ":", v,
                               gpuCamera(cam, ctx.pixelSpread(v)), draw, vis);
    } else {
      cmd.fill(vis, 0, pixels * sizeof(uint64_t), 0);
      counters.push_back(
          recordRasterizer(gpu, scene, sceneAddress, queueBuffer,
                           RasterView{&cam, ctx.pixelSpread(v), &draw, &vis, /*bothFaces=*/false}));
    }
    RasterResolveArgs r{};
    r.scene = sceneAddress;
    r.view = gpuViewConstants(ctx, v);
    r.targets = targets;
    r.motion = motion;
    r.visibility = vis.address;
    r.hdr = hdr;
    r.viewX = v.x;
    r.viewY = v.y;
    r.frameWidth = ctx.width;
    r.objectCount = uint32_t(fs.objects.size());
    resolves.push_back(r);
  }
  // The resolves after every view's visibility: one part each, as on the CPU.
  const uint32_t t1 = cmd.timestamp();
  for (size_t vi = 0; vi < ctx.views.size(); ++vi) {
    const View& v = ctx.views[vi];
    gpu.dispatchInterruptibly(resolve, uint32_t(v.width() + 7) / 8, uint32_t(v.height() + 7) / 8,
                              &resolves[vi]);
  }
  const uint32_t t2 = cmd.timestamp();
  std::vector<const uint32_t*> counts;
  for (uint64_t c : counters) counts.push_back(static_cast<const uint32_t*>(gpu.constantsData(c)));
  gpu.afterSubmit([&ctx, &pass, &cmd, counts, in, culledOnHost, t0, t1, t2, resolvePart, graphics] {
    double culled = culledOnHost, clipped = 0, binned = 0;
    for (const uint32_t* c : counts) {
      culled += c[TD_RASTER_CULLED];
      clipped += c[TD_RASTER_CLIPPED];
      binned += c[TD_RASTER_BINNED];
    }
    ctx.report(pass, RasterCounters::trianglesIn, in);
    ctx.report(pass, RasterCounters::trianglesCulled, culled);
    if (!graphics) {
      ctx.report(pass, RasterCounters::trianglesClipped, clipped);
      ctx.report(pass, RasterCounters::trianglesBinned, binned);
    }
    ctx.passParts.push_back({"visibility", cmd.activeMs(t0, t1), 0});
    ctx.passParts.push_back({resolvePart, cmd.activeMs(t1, t2), 0});
  });
}

}  // namespace tandem
