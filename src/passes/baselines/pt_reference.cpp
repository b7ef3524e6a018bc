#include "passes/baselines/pt_reference.h"

#include <cmath>
#include <cstring>

#include "core/interrupt.h"
#include "gpu/gpu_camera.h"
#include "gpu/shaders/reference_args.h"
#include "gpu/shaders/reference_spv.h"
#include "gpu/shaders/whitted_args.h"
#include "passes/common/gpu_light_grid.h"
#include "passes/common/gpu_whitted.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "rt/reference_render.h"
#include "shading/surface_resolve.h"

namespace tandem {

const ParamTable<PTReferenceSettings>& PTReferencePass::tableFor() const {
  using S = PTReferenceSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::spp,
               {.name = "spp", .min = 1, .max = 1 << 20, .doc = "target samples per pixel"})
          .add(&S::timeLimit, {.name = "time_limit",
                               .min = 0,
                               .max = 1e7,
                               .doc = "seconds; > 0 stops at the last batch that fits"})
          .add(&S::maxDepth, {.name = "max_depth",
                              .min = 1,
                              .max = 1024,
                              .doc = "maximum path length in bounces",
                              .invalidatesHistory = true})
          .add(&S::progress, {.name = "progress", .doc = "progress bar on a terminal's stderr"})
          .add(&S::accumulate,
               {.name = "accumulate",
                .doc = "keep converging over frames while nothing changes (viewer)"})
          .add(&S::frameSpp, {.name = "frame_spp",
                              .min = 1,
                              .max = 1024,
                              .doc = "accumulate: samples added per frame"})
          .add(&S::integrator,
               {.name = "integrator",
                .doc = "path: path tracing (global illumination); whitted: distributed ray tracing "
                       "of the hybrids' shading (shadows, mirrors, glass; the same light transport "
                       "as rt-only); diffuse-gi: the foveated pipelines' path tracer, converged",
                .choices = {"path", "whitted", "diffuse-gi"},
                .invalidatesHistory = true})
          .add(&S::whittedDepth,
               {.name = "whitted_depth",
                .min = 1,
                .max = 64,
                .doc = "whitted: recursion depth of secondary rays (rt_whitted's max_depth)",
                .invalidatesHistory = true});
  return table;
}

std::vector<CounterDesc> PTReferencePass::counters() const {
  return {
      {PTReferenceCounters::spp, "samples per pixel accumulated so far"},
  };
}

void PTReferencePass::execute(FrameContext& ctx) {
  const auto t0 = Clock::now();
  RayTracer& rt = ctx.rayTracer();  // (re)builds the BVH: reported apart from the sampling
  ctx.passParts.push_back({"bvh", msSince(t0), 0});
  SampleCluster single;
  SampleCluster& cluster = cluster_ ? *cluster_ : single;
  render(ctx, [&](const View& v, const ReferenceSettings& eye, SampleSums& sums) {
    return renderReference(rt, *ctx.scene, v.camera, v.shutterCamera, eye, cluster, sums);
  });
}

void PTReferencePass::render(
    FrameContext& ctx,
    const std::function<ReferenceResult(const View&, const ReferenceSettings&, SampleSums&)>&
        renderView) {
  const PTReferenceSettings& s = settings();
  ReferenceSettings ref;
  ref.spp = s.spp;
  ref.timeLimitS = s.timeLimit;
  ref.path.maxDepth = s.maxDepth;
  ref.integrator = s.integrator;
  ref.whitted.maxDepth = s.whittedDepth;
  ref.progress = s.progress;
  ref.seed = frameSeed(ctx.seed, ctx.frameIndex);
  const bool accumulate = s.accumulate;
  if (accumulate) {
    // Samples continue by index, so the frame number must not change the sequence.
    ref.seed = frameSeed(ctx.seed, 0);
    // History resets (scene, size, pipeline, lens, max_depth) clear sums_; a moved camera or
    // moved geometry starts over too (scene time matters only through moved geometry).
    if (ctx.anyCameraMoved() || ctx.frame.geometryVersion != geometryVersion_) sums_.clear();
    geometryVersion_ = ctx.frame.geometryVersion;
    ref.timeLimitS = 0;
    ref.progress = false;
  } else {
    sums_.clear();
  }
  sums_.resize(ctx.views.size());
  Buffer& hdr = ctx.output(*this, Slots::hdr);
  Buffer& variance = ctx.output(*this, Slots::variance);
  int spp = 0;
  double seconds = 0;
  for (size_t i = 0; i < ctx.views.size(); ++i) {
    const View& v = ctx.views[i];
    SampleSums& sums = sums_[i];
    if (sums.width != v.width() || sums.height != v.height()) sums.reset(v.width(), v.height());
    ReferenceSettings eye = ref;
    eye.seed += uint64_t(i) * 0xD1B54A32D192ED03ull;  // eyes get independent samples
    if (accumulate) eye.spp = std::min(ref.spp, sums.samples + s.frameSpp);
    ReferenceResult r = renderView(v, eye, sums);
    spp = i == 0 ? r.spp : std::min(spp, r.spp);
    seconds += r.seconds;
    ctx.passRays += double(r.rays);
    if (ctx.views.size() == 1) {
      sums.resolve(hdr, &variance);
    } else {
      Buffer h(v.width(), v.height(), 3), var(v.width(), v.height(), 1);
      sums.resolve(h, &var);
      for (int y = 0; y < v.height(); ++y)
        for (int x = 0; x < v.width(); ++x) {
          hdr.setRgb(x + v.x, y + v.y, h.rgb(x, y));
          variance.at(x + v.x, y + v.y)[0] = var.at(x, y)[0];
        }
    }
  }
  ctx.report(*this, PTReferenceCounters::spp, spp);
  ctx.passParts.push_back({"sampling", seconds * 1e3, ctx.passRays});
}

bool PTReferencePass::hasGpu() const {
  return true;  // shaders/reference.comp, each MPI rank on its own stripes
}

namespace {
// EmitterTable's triangles as the GPU samples them (chosen in proportion to area x emitted
// luminance), and each object's first one in `objectFirst` (-1: not emissive).
std::vector<GpuEmitter> gpuEmitters(const FrameScene& fs, std::vector<int32_t>& objectFirst) {
  const Scene& scene = *fs.scene;
  std::vector<GpuEmitter> emitters;
  objectFirst.assign(std::max<size_t>(fs.objects.size(), 1), -1);
  std::vector<double> weights;
  double total = 0;
  for (size_t o = 0; o < fs.objects.size(); ++o) {
    const Material& m = scene.materials[size_t(scene.objects[o].material)];
    const float lum = (m.emission.x + m.emission.y + m.emission.z) * (1.0f / 3.0f);
    if (!(lum > 0.0f)) continue;
    const Mesh& mesh = scene.meshes[size_t(scene.objects[o].mesh)];
    const std::vector<Vec3>& p = fs.objects[o].positions;
    objectFirst[o] = int32_t(emitters.size());
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const Vec3 a = p[mesh.indices[3 * t]], b = p[mesh.indices[3 * t + 1]],
                 c = p[mesh.indices[3 * t + 2]];
      const float area = 0.5f * length(cross(b - a, c - a));
      emitters.push_back({int32_t(o), int32_t(t), area, 0.0f});
      weights.push_back(double(area * lum));
      total += weights.back();
    }
  }
  double cdf = 0;
  for (size_t k = 0; k < emitters.size(); ++k) {
    const float area = emitters[k].pdfArea;
    cdf += weights[k];
    emitters[k].pdfArea = area > 0.0f ? float(weights[k] / total) / area : 0.0f;
    emitters[k].cdf = float(cdf / total);
  }
  return emitters;
}
// The arguments every sample of the frame shares: the scene, its emitters and light grid, the
// integrator's settings and this process's rows.
ReferenceArgs sceneArgs(FrameContext& ctx, const PTReferenceSettings& s,
                        const SampleCluster& cluster) {
  GpuFrame& gpu = *ctx.gpu;
  const FrameScene& fs = ctx.frame;
  const Scene& scene = *ctx.scene;
  const uint64_t sceneAddress = gpu.scene(fs).sceneAddress();
  std::vector<int32_t> objectFirst;
  const std::vector<GpuEmitter> emitters = gpuEmitters(fs, objectFirst);
  std::vector<uint32_t> lightSkip(std::max<size_t>(scene.lights.size(), 1), 0);
  for (size_t i = 0; i < scene.lights.size(); ++i) lightSkip[i] = scene.lights[i].fromEmissiveMesh;
  const GpuEmitter none{};
  ReferenceArgs a{};
  a.scene = sceneAddress;
  a.emitters = emitters.empty()
                   ? gpu.constants(&none, sizeof none)
                   : gpu.constants(emitters.data(), emitters.size() * sizeof(GpuEmitter));
  a.emitterCount = uint32_t(emitters.size());
  a.objectFirst = gpu.constants(objectFirst.data(), objectFirst.size() * sizeof(int32_t));
  a.lightSkip = gpu.constants(lightSkip.data(), lightSkip.size() * sizeof(uint32_t));
  const uint32_t zero = 0;
  a.counters = gpu.constants(&zero, sizeof zero);
  a.maxDepth = s.maxDepth;
  a.rouletteDepth = PathSettings{}.rouletteDepth;
  a.integrator = s.integrator == Integrator::Whitted     ? TD_REFERENCE_WHITTED
                 : s.integrator == Integrator::DiffuseGI ? TD_REFERENCE_DIFFUSE_GI
                                                         : TD_REFERENCE_PATH;
  // diffuse-gi picks its lights by the grid renderReference builds: built on the host (its
  // visibility probes are the CPU's rays, once a render) and copied to the device.
  if (a.integrator == TD_REFERENCE_DIFFUSE_GI) {
    const LightGrid grid =
        DiffuseGI::buildGrid(scene, ShadingContext::from(scene), &ctx.rayTracer());
    a.grid = gpuLightGrid(gpu, &grid, {});
  } else {
    a.grid = gpuLightGrid(gpu, nullptr, {});  // unused
  }
  const WhittedSettings w = [&] {
    WhittedSettings ws;
    ws.maxDepth = s.whittedDepth;
    return ws;
  }();
  a.whittedDepth = w.maxDepth;
  a.importanceCutoff = w.importanceCutoff;
  a.shadowCull = w.shadowCull;
  a.whittedFlags = gpuWhittedFlags(w);
  a.rank = uint32_t(cluster.rank());
  a.ranks = uint32_t(cluster.ranks());
  a.stripeRows = SampleCluster::kStripeRows;
  return a;
}
}  // namespace

void PTReferencePass::executeGpu(FrameContext& ctx) {
  // An open shutter renders here: each sample's camera and moving objects where they are at its
  // time (GpuScene keeps the time steps). Processes sharing the rows (MPI) each trace their own
  // stripes on their device, and the sums meet on rank 0 as the CPU's do.
  SampleCluster single;
  SampleCluster& cluster = cluster_ ? *cluster_ : single;
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  ReferenceArgs a = sceneArgs(ctx, settings(), cluster);
  const GpuKernel& k =
      gpu.kernel("reference", kReferenceSpv, sizeof(kReferenceSpv) / 4, sizeof(uint64_t));
  const auto* rays = static_cast<const uint32_t*>(gpu.constantsData(a.counters));
  render(ctx, [&](const View& v, const ReferenceSettings& eye, SampleSums& sums) {
    const Camera& cam = v.camera;
    const GpuCamera gc = gpuCamera(cam, 0.0f);
    a.camera = gpu.constants(&gc, sizeof gc);
    const CameraDesc &open = cam.desc, &close = v.shutterCamera.desc;
    a.cameraMoves = std::memcmp(&open.position, &close.position, sizeof(Vec3)) ||
                    std::memcmp(&open.lookAt, &close.lookAt, sizeof(Vec3));
    auto put = [](float* out, Vec3 p) { out[0] = p.x, out[1] = p.y, out[2] = p.z; };
    put(a.openLookAt, open.lookAt);
    put(a.closePosition, close.position);
    put(a.closeLookAt, close.lookAt);
    put(a.cameraUp, open.up);
    a.pixelSpread = pixelSpreadAngle(cam);
    a.apertureRadius = 0.5f * cam.desc.apertureDiameter;
    a.focusDistance = cam.desc.focusDistance;
    a.apertureRotation = radians(cam.desc.apertureRotationDeg);
    a.apertureBlades = cam.desc.apertureBlades;
    a.seedLo = uint32_t(eye.seed);
    a.seedHi = uint32_t(eye.seed >> 32);
    const size_t pixels = size_t(cam.width) * size_t(cam.height);
    // The batch's sums in device memory, which every sample reads and writes, read back once a
    // batch into cached host memory (GpuMemory's Readback).
    const size_t sumBytes = pixels * 4 * sizeof(float);
    const GpuBuffer& sumsBuffer = gpu.scratch(name() + ":sums", sumBytes);
    cmd.fill(sumsBuffer, 0, sumBytes, 0);
    cmd.barrier();
    a.sums = sumsBuffer.address;
    std::vector<float> batchSums(pixels * 4);
    const uint32_t raysBefore = *rays;
    const auto start = Clock::now();
    ReferenceResult result;
    while (sums.samples < eye.spp) {
      // As renderReference: batches double up to 64, within the time limit.
      int batch = std::min({eye.spp - sums.samples, std::max(sums.samples, 1), 64});
      if (eye.timeLimitS > 0 && sums.samples > 0) {
        const double perSample = msSince(start) * 1e-3 / double(sums.samples);
        const double left = eye.timeLimitS - msSince(start) * 1e-3;
        batch = std::min(batch, int(std::floor(left / std::max(perSample, 1e-9))));
      }
      batch = cluster.broadcast(std::max(batch, 0));  // every process stops at rank 0's count
      if (batch <= 0) break;
      // One dispatch a sample (a loop over the batch inside one invocation drifted from the CPU's
      // samples on lavapipe after 16 or so: not understood, so not relied on). On a CPU Vulkan
      // each is submitted alone, Ctrl-C honoured between them.
      const bool hardware = gpu.device().info().hardware;
      for (int i = 0; i < batch; ++i) {
        a.first = uint32_t(sums.samples + i);
        const uint64_t args = gpu.constants(&a, sizeof a);
        cmd.dispatch(k, uint32_t(cam.width + 7) / 8, uint32_t(cam.height + 7) / 8, 1, &args);
        cmd.barrier();
        if (!hardware && i + 1 < batch) {
          cmd.checkpoint();
          pollInterrupt();
        }
      }
      gpu.readBack(sumsBuffer, sumBytes, batchSums.data());  // a checkpoint
      pollInterrupt();                                       // a stop keeps whole samples
      for (size_t i = 0; i < pixels * 4; ++i) sums.data[i] += double(batchSums[i]);
      cmd.fill(sumsBuffer, 0, sumBytes, 0);  // the next batch's sums start at 0
      cmd.barrier();
      sums.samples += batch;
    }
    result.seconds = msSince(start) * 1e-3;
    cluster.reduceSum(sums.data);  // other processes' rows are 0 here: the sum is exact
    std::vector<double> traced{double(*rays - raysBefore)};
    cluster.reduceSum(traced);  // every process's rays, on rank 0
    result.spp = sums.samples;
    result.rays = uint64_t(traced[0]);
    if (cluster.rank() == 0) result.relativeError = sums.relativeError();
    return result;
  });
}

}  // namespace tandem
