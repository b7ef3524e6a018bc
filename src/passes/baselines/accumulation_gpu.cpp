// accumulation on the GPU: each pair of T a full frame drawn by the compute rasterizer
// (gpu_visible_surfaces.h) at its time and lens point, then shaded and added into hdr
// (shaders/accumulation.comp), pairs in the CPU's order. Objects moving in the shutter are drawn
// and traced where they are at the pair's time (their time steps on the device).
#include <algorithm>
#include <vector>

#include "gpu/gpu_camera.h"
#include "gpu/shaders/accumulation_args.h"
#include "gpu/shaders/accumulation_spv.h"
#include "gpu/shaders/raster_args.h"
#include "passes/baselines/accumulation.h"
#include "passes/common/gpu_visible_surfaces.h"
#include "passes/common/gpu_whitted.h"
#include "passes/common/time_lens_camera.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "raster/rasterizer.h"
#include "rt/reference_render.h"
#include "scene/scene.h"

namespace tandem {

void AccumulationPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const AccumulationSettings& s = settings();
  const int n = s.samples;
  const bool lens = s.mode != AccumulationSettings::Mode::MotionBlur,
             time = s.mode != AccumulationSettings::Mode::Dof, aa = s.antialias;
  const Scene& scene = *ctx.scene;
  const std::vector<TimeLensPair> pairs = stratifiedTimeLensPairs(n, ctx.seed);
  AccumulationArgs a{};
  a.hdr = ctx.deviceOutput(*this, Slots::hdr);
  const GpuBuffer& hdr = gpu.read(bufferName(Slots::hdr));
  cmd.fill(hdr, 0, hdr.size, 0);
  cmd.barrier();
  const uint32_t zero = 0;
  a.counters = gpu.constants(&zero, sizeof zero);
  a.frameWidth = uint32_t(ctx.width);
  a.objectCount = uint32_t(ctx.frame.objects.size());
  a.whittedShading = s.shading == AccumulationSettings::Shading::Whitted ? 1u : 0u;
  a.weight = 1.0f / float(n);
  const WhittedSettings ws{};  // AccumulationPass::execute's Whitted: the defaults, no maps
  a.maxDepth = ws.maxDepth;
  a.whittedFlags = gpuWhittedFlags(ws);
  a.importanceCutoff = ws.importanceCutoff;
  a.shadowCull = ws.shadowCull;
  size_t triangles = 0;
  for (const Object& o : scene.objects) triangles += scene.meshes[size_t(o.mesh)].triangleCount();
  const RasterQueue queue = rasterQueue(gpu, "raster:" + name() + ":queue", triangles);
  const GpuKernel& k =
      gpu.kernel("accumulation", kAccumulationSpv, sizeof(kAccumulationSpv) / 4, sizeof(uint64_t));
  std::vector<uint64_t> counters;
  for (const View& v : ctx.views) {
    const size_t pixels = size_t(v.width()) * size_t(v.height());
    const GpuBuffer& vis = gpu.scratch(name() + ":visibility", pixels * sizeof(uint64_t));
    a.viewX = v.x;
    a.viewY = v.y;
    for (const TimeLensPair& p : pairs) {
      const float tau = time ? p.tau : 0.0f;
      const Camera cam = cameraForPair(v, p, time, lens, aa ? v.jitter + p.jitter : v.jitter);
      const FrameScene& fs = ctx.frame;
      // Moving objects keep their time steps on the device: drawn and traced at the pair's time.
      a.scene = gpu.scene(fs).sceneAddress();
      a.tau = tau;
      std::vector<uint32_t> draw(std::max<size_t>(fs.objects.size(), 1), 0);
      for (size_t o = 0; o < fs.objects.size(); ++o)
        draw[o] = boundsOutsideFrustum(cam.viewProj, fs.objects[o].bounds) ? 0 : 1;
      cmd.fill(vis, 0, pixels * sizeof(uint64_t), 0);
      cmd.barrier();
      counters.push_back(recordRasterizer(
          gpu, scene, a.scene, queue, RasterView{&cam, 0.0f, &draw, &vis, false, nullptr, tau}));
      cmd.barrier();
      const GpuCamera gc = gpuCamera(cam, 0.0f);
      a.camera = gpu.constants(&gc, sizeof gc);
      a.visibility = vis.address;
      const uint64_t args = gpu.constants(&a, sizeof a);
      gpu.dispatchInterruptibly(k, uint32_t(v.width() + 7) / 8, uint32_t(v.height() + 7) / 8,
                                &args);
      cmd.barrier();  // the next pair draws into the same visibility buffer
    }
  }
  std::vector<const uint32_t*> counts;
  for (uint64_t c : counters) counts.push_back(static_cast<const uint32_t*>(gpu.constantsData(c)));
  const auto* rays = static_cast<const uint32_t*>(gpu.constantsData(a.counters));
  gpu.afterSubmit([this, &ctx, counts, rays] {
    double binned = 0;
    for (const uint32_t* c : counts) binned += c[TD_RASTER_BINNED];
    ctx.report(*this, AccumulationCounters::trianglesBinned, binned);
    ctx.passRays += *rays;
  });
}

}  // namespace tandem
