// interleaved_rt and interleaved_raster on the GPU (shaders/interleaved.comp): the CPU's pairs,
// tiles and sample layout (the layout moved to the device when it changes); for the raster, each
// pair's samples drawn by the compute rasterizer in sample mode; each pair's samples traced (rt)
// and shaded at the pair's time (the scene's moving objects keep their time steps on the device:
// the raster draws and the rays meet them where they are then), then the resolve and the motion
// buffers. A pixel's shading rate finds every sample's surface
// first (drawn, or traced into the raster's keys), then shades each pixel's representatives.
#include <cstring>
#include <vector>

#include "gpu/gpu_camera.h"
#include "gpu/shaders/interleaved_args.h"
#include "gpu/shaders/interleaved_spv.h"
#include "gpu/shaders/raster_args.h"
#include "gpu/shaders/whitted_args.h"
#include "passes/common/gpu_shadow_maps.h"
#include "passes/common/gpu_visible_surfaces.h"
#include "passes/common/gpu_whitted.h"
#include "passes/interleaved/interleaved_raster.h"
#include "passes/interleaved/interleaved_rt.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "raster/rasterizer.h"
#include "scene/scene.h"

namespace tandem {

namespace {

void putMatrix(float out[16], const Mat4& m) {
  std::memcpy(out, &m.m[0][0], 16 * sizeof(float));
}

// The layout as the kernels read it: per sample its position (float and fixed point) and pair;
// the samples in pair order; each pair's cells' starts.
void packLayout(const SampleLayout& L, std::vector<Buffer>& out) {
  out.assign(5, Buffer());
  const size_t n = L.sampleCount();
  out[0] = Buffer(int(n), 1, 2);  // pos
  out[1] = Buffer(int(n), 1, 1);  // pair
  out[2] = Buffer(int(n), 1, 2);  // fixed
  for (size_t i = 0; i < n; ++i) {
    const uint32_t pair = L.pair[i];
    out[0].data[2 * i] = L.pos[i].x;
    out[0].data[2 * i + 1] = L.pos[i].y;
    std::memcpy(&out[1].data[i], &pair, sizeof pair);
    std::memcpy(&out[2].data[2 * i], &L.fx[i], sizeof(int32_t));
    std::memcpy(&out[2].data[2 * i + 1], &L.fy[i], sizeof(int32_t));
  }
  out[3] = Buffer(int(L.ids.size()), 1, 1);
  std::memcpy(out[3].data.data(), L.ids.data(), L.ids.size() * sizeof(uint32_t));
  out[4] = Buffer(int(L.cellStart.size()), 1, 1);
  std::memcpy(out[4].data.data(), L.cellStart.data(), L.cellStart.size() * sizeof(uint32_t));
}
constexpr const char* kLayoutParts[5] = {":pos", ":pair", ":fixed", ":ids", ":start"};

// The shading's arguments: Whitted's settings and the frame's shadow maps on the device.
void shadingArgs(FrameContext& ctx, const InterleavedPass& pass, InterleavedArgs& a) {
  const InterleavedSettings& s = pass.settings();
  const bool whittedShading = s.shading == InterleavedSettings::Shading::Whitted;
  const ShadowMaps* maps =
      whittedShading ? shadowMapsFor(ctx, pass, s.whitted, nullptr, true) : nullptr;
  a.shadowMaps = maps ? gpuShadowMaps(ctx, *maps) : 0;
  const WhittedSettings ws = s.whitted.settings();
  a.whittedFlags = gpuWhittedFlags(ws, maps != nullptr);
  a.maxDepth = ws.maxDepth;
  a.importanceCutoff = ws.importanceCutoff;
  a.shadowCull = ws.shadowCull;
  a.flags |= (whittedShading ? TD_IL_WHITTED : 0u) | (s.time() ? TD_IL_TIME : 0u) |
             (s.lens() ? TD_IL_LENS : 0u);
}

// The resolve's filter: its reach and its 1D weight, tabulated as InterleavedPass::resolve
// tabulates it.
void filterArgs(GpuFrame& gpu, const InterleavedSettings& s, InterleavedArgs& a) {
  a.reach = int(std::ceil(s.filterRadius - 0.5f));
  a.radius = s.filterRadius;
  std::vector<float> table(TD_IL_TABLE + 2);
  const bool bh = s.filter == InterleavedSettings::Filter::BlackmanHarris;
  for (int i = 0; i <= TD_IL_TABLE + 1; ++i)
    table[size_t(i)] = i > TD_IL_TABLE ? 0.0f : bh ? blackmanHarris(float(i) / TD_IL_TABLE) : 1.0f;
  a.weights = gpu.constants(table.data(), table.size() * sizeof(float));
  a.toTable = float(TD_IL_TABLE) / s.filterRadius;
}

// Each pair's constants for view v (IlPair[n] and IlCarry[n * objects] into `a`): its camera
// and time, and for motion its cameras of this and last frame and its objects' carry matrices.
void fillPairs(GpuFrame& gpu, const std::vector<float>& taus, const std::vector<Camera>& cams,
               const std::vector<std::vector<std::pair<Mat4, Mat4>>>& carryTo,
               const std::vector<std::vector<Mat4>>& carryPrev, const std::vector<Camera>& nowCams,
               const std::vector<Camera>& prevCams, size_t objects, InterleavedArgs& a) {
  const size_t n = taus.size();
  std::vector<IlPair> pairs(n);
  std::vector<IlCarry> carry(n * objects);
  for (size_t j = 0; j < n; ++j) {
    pairs[j].camera = gpuCamera(cams[j], 0.0f);
    pairs[j].tau = taus[j];
    if (a.motion) {
      putMatrix(pairs[j].nowViewProj, nowCams[j].viewProjUnjittered);
      putMatrix(pairs[j].prevViewProj, prevCams[j].viewProjUnjittered);
    }
    for (size_t o = 0; o < carryTo[j].size(); ++o) {
      IlCarry& c = carry[j * objects + o];
      putMatrix(c.open, carryTo[j][o].first);
      putMatrix(c.close, carryTo[j][o].second);
      putMatrix(c.prev, carryPrev[j][o]);
    }
  }
  a.pairs = gpu.constants(pairs.data(), pairs.size() * sizeof(IlPair));
  a.carry = gpu.constants(carry.data(), carry.size() * sizeof(IlCarry));
}

// The frame's buffers, the resolve's filter, the tiles' shape, which objects are animated (for
// the motion's carry matrices, a slot per object, at least one) and the counters.
void frameArgs(FrameContext& ctx, const InterleavedPass& pass, const TileShape& shape,
               InterleavedArgs& a) {
  using Slots = InterleavedPass::Slots;
  GpuFrame& gpu = *ctx.gpu;
  a.hdr = ctx.deviceOutput(pass, Slots::hdr);
  a.velocity = ctx.deviceOutput(pass, Slots::velocity);
  a.depth = ctx.deviceOutput(pass, Slots::viewDepth);
  a.motion = ctx.deviceOutputIfConsumed(pass, Slots::motion);
  a.mask =
      ctx.optionalInput(pass, Slots::sampleMask) ? ctx.deviceInput(pass, Slots::sampleMask) : 0;
  filterArgs(gpu, pass.settings(), a);
  a.frameWidth = uint32_t(ctx.width);
  a.sx = shape.sx;
  a.sy = shape.sy;
  a.objectCount = int(ctx.scene->objects.size());
  std::vector<uint32_t> animated(std::max<size_t>(ctx.scene->objects.size(), 1), 0);
  for (size_t o = 0; o < ctx.scene->objects.size(); ++o)
    animated[o] = ctx.scene->objects[o].animated() ? 1u : 0u;
  a.animated = gpu.constants(animated.data(), animated.size() * sizeof(uint32_t));
  const std::vector<uint32_t> zero(TD_COUNT_N, 0);
  a.counters = gpu.constants(zero.data(), zero.size() * sizeof(uint32_t));
}

// Pass j's samples drawn by the compute rasterizer in sample mode into `vis` (the scene at
// `sceneAddress`); the address of its counters.
uint64_t drawPassSamples(FrameContext& ctx, const SampleLayout& L, const uint64_t parts[5], int j,
                         const Camera& cam, float tau, uint64_t sceneAddress, float pixelSpread,
                         const GpuBuffer& vis, const std::string& queueKey) {
  GpuFrame& gpu = *ctx.gpu;
  size_t triangles = 0;
  for (const Object& o : ctx.scene->objects)
    triangles += ctx.scene->meshes[size_t(o.mesh)].triangleCount();
  const RasterQueue queue = rasterQueue(gpu, queueKey, triangles);
  std::vector<uint32_t> draw(std::max<size_t>(ctx.frame.objects.size(), 1), 0);
  for (size_t o = 0; o < ctx.frame.objects.size(); ++o)
    draw[o] = boundsOutsideFrustum(cam.viewProj, ctx.frame.objects[o].bounds) ? 0 : 1;
  RasterSamples rs;
  rs.start = parts[4] + uint64_t(j) * uint64_t(L.cells() + 1) * sizeof(uint32_t);
  rs.ids = parts[3];
  rs.fixedPos = parts[2];
  rs.pos = parts[0];
  rs.cellW = L.shape.tw;
  rs.cellH = L.shape.th;
  rs.cellsX = L.cellsX;
  rs.cellsY = L.cellsY;
  return recordRasterizer(gpu, *ctx.scene, sceneAddress, queue,
                          RasterView{&cam, pixelSpread, &draw, &vis, false, &rs, tau});
}

}  // namespace

std::vector<const uint32_t*> InterleavedPass::renderOnGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const InterleavedSettings& s = settings();
  const Pairs p = framePairs(ctx);
  const TileShape& shape = p.tiles->shape;
  const int n = s.samples;
  const bool whittedShading = s.shading == InterleavedSettings::Shading::Whitted;
  const bool raster = !tracesPrimaryRays();
  const bool perPixel = s.shadingRate == InterleavedSettings::ShadingRate::Pixel;
  InterleavedArgs a{};
  shadingArgs(ctx, *this, a);
  a.flags |= (raster ? TD_IL_RASTER : 0u) | (perPixel ? TD_IL_PER_PIXEL : 0u);
  frameArgs(ctx, *this, shape, a);
  const size_t objectSlots = std::max<size_t>(ctx.scene->objects.size(), 1);
  std::vector<uint64_t> rasterCounts;  // the rasterizer's counters, a pair a view
  const GpuKernel& k = gpu.kernel("interleaved", kInterleavedSpv, sizeof(kInterleavedSpv) / 4,
                                  sizeof(InterleavedPush));
  const auto rows = [](uint64_t entries) { return uint32_t((entries + 4095) / 4096); };
  for (const View& v : ctx.views) {
    const int W = v.width(), H = v.height();
    const SampleLayout& L = layoutFor(ctx, *p.tiles, W, H);
    if (packedVersion_ != layoutVersion() || packed_.size() != 5) {
      packLayout(L, packed_);
      packedVersion_ = layoutVersion();
      for (const char* part : kLayoutParts) gpu.hostWrote(name() + part);
    }
    uint64_t parts[5];
    for (int b = 0; b < 5; ++b) {
      const std::string key = name() + kLayoutParts[b];
      gpu.upload(key, packed_[size_t(b)]);
      parts[b] = gpu.read(key).address;
    }
    a.samplePos = parts[0];
    a.samplePair = parts[1];
    a.ids = parts[3];
    const size_t samples = L.sampleCount();
    a.colour = gpu.scratch(name() + ":colour", samples * 3 * sizeof(float)).address;
    a.position = gpu.scratch(name() + ":position", samples * 3 * sizeof(float)).address;
    a.object = gpu.scratch(name() + ":object", samples * sizeof(uint32_t)).address;
    a.rep = perPixel ? gpu.scratch(name() + ":rep", samples * sizeof(uint32_t)).address : 0;
    a.viewX = v.x, a.viewY = v.y, a.width = W, a.height = H;
    a.spread = ctx.pixelSpread(v) / std::sqrt(float(s.spp)) * s.textureFootprint;
    const std::vector<Camera> cams = pairCameras(v, p);
    const MotionCarry mc = motionCarry(ctx, p.taus, v, a.motion != 0);
    fillPairs(gpu, p.taus, cams, mc.carry, mc.carryPrev, mc.nowCams, mc.prevCams, objectSlots, a);
    putMatrix(a.openViewProj, v.camera.viewProjUnjittered);
    putMatrix(a.closeViewProj, v.shutterCamera.viewProjUnjittered);
    // The frame's scene, its moving objects with their time steps: each pair draws and traces
    // them where they are at its time.
    a.scene = gpu.scene(ctx.frame).sceneAddress();
    // 1. With the raster, or a pixel's shading rate, visibility before any shading (the CPU
    // finds every sample's surface first): each pair's samples drawn, or traced, into keys.
    if (raster || perPixel) {
      const GpuBuffer& vis = gpu.scratch(name() + ":visibility", samples * sizeof(uint64_t));
      a.visibility = vis.address;
      cmd.fill(vis, 0, samples * sizeof(uint64_t), 0);
      cmd.barrier();
      for (int j = 0; j < n; ++j) {
        if (raster) {
          rasterCounts.push_back(drawPassSamples(ctx, L, parts, j, cams[size_t(j)],
                                                 p.taus[size_t(j)], a.scene, ctx.pixelSpread(v),
                                                 vis, name() + ":queue"));
        } else {
          const uint32_t begin = L.passBegin(j), count = L.passEnd(j) - begin;
          InterleavedPush push{gpu.constants(&a, sizeof a), TD_IL_TRACE, uint32_t(j), begin, count};
          if (count > 0) gpu.dispatchInterruptibly(k, 64, rows(count), &push);
        }
        cmd.barrier();
      }
      if (perPixel) {
        InterleavedPush push{gpu.constants(&a, sizeof a), TD_IL_REPRESENT, 0, 0, uint32_t(samples)};
        cmd.dispatch(k, 64, rows(samples), 1, &push);
        cmd.barrier();
      }
    }
    for (int j = 0; j < n; ++j) {  // 2. each pair's samples traced (rt) and shaded
      const uint32_t begin = L.passBegin(j), count = L.passEnd(j) - begin;
      InterleavedPush push{gpu.constants(&a, sizeof a), TD_IL_SHADE, uint32_t(j), begin, count};
      if (count > 0) gpu.dispatchInterruptibly(k, 64, rows(count), &push);
    }
    if (perPixel) {
      cmd.barrier();
      InterleavedPush push{gpu.constants(&a, sizeof a), TD_IL_COPY, 0, 0, uint32_t(samples)};
      cmd.dispatch(k, 64, rows(samples), 1, &push);
    }
    cmd.barrier();
    InterleavedPush push{gpu.constants(&a, sizeof a), TD_IL_RESOLVE, 0, 0, 0};
    cmd.dispatch(k, 64, rows(uint64_t(W) * H), 1, &push);
    push.stage = TD_IL_MOTION;
    cmd.dispatch(k, 64, rows(uint64_t(W) * H), 1, &push);
    cmd.barrier();  // the next view's samples overwrite these
    writeViewerBuffers(ctx, p, v);
  }
  reportTiles(ctx, *p.tiles);
  const auto* counts = static_cast<const uint32_t*>(gpu.constantsData(a.counters));
  const double pixels = double(ctx.width) * double(ctx.height);
  gpu.afterSubmit([this, &ctx, counts, pixels, whittedShading] {
    ctx.passRays += counts[TD_COUNT_RAYS];
    if (whittedShading) reportGpuShadows(ctx, *this, counts, pixels);
  });
  std::vector<const uint32_t*> out;
  for (uint64_t c : rasterCounts) out.push_back(static_cast<const uint32_t*>(gpu.constantsData(c)));
  return out;
}

void InterleavedRTPass::executeGpu(FrameContext& ctx) {
  renderOnGpu(ctx);
}

void InterleavedRasterPass::executeGpu(FrameContext& ctx) {
  const std::vector<const uint32_t*> counts = renderOnGpu(ctx);
  ctx.gpu->afterSubmit([this, &ctx, counts] {
    double setUp = 0, most = 0, least = 1e300;
    for (const uint32_t* c : counts) {
      const double binned = c[TD_RASTER_BINNED];
      setUp += binned;
      most = std::max(most, binned);
      least = std::min(least, binned);
    }
    using C = InterleavedRasterCounters;
    ctx.report(*this, C::setUpPerPass, counts.empty() ? 0.0 : setUp / double(counts.size()));
    ctx.report(*this, C::setUpMax, most);
    ctx.report(*this, C::setUpMin, std::min(least, most));
    ctx.report(*this, C::staticSetUpOnce, 0.0);  // every pass draws every object
  });
}

}  // namespace tandem
