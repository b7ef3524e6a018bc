// interleaved_rt on the GPU (shaders/interleaved.comp): the CPU's pairs, tiles and sample layout
// (the layout moved to the device when it changes), each pair's samples traced and shaded with
// the scene at the pair's time (the GPU's BVH has no time: between pairs of a shutter with moving
// objects the host moves them and refits, one submission a pair), then the resolve and the
// motion buffers.
#include <cstring>
#include <vector>

#include "gpu/gpu_camera.h"
#include "gpu/shaders/interleaved_args.h"
#include "gpu/shaders/interleaved_spv.h"
#include "gpu/shaders/whitted_args.h"
#include "passes/common/gpu_shadow_maps.h"
#include "passes/common/gpu_whitted.h"
#include "passes/interleaved/interleaved_rt.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "scene/scene.h"

namespace tandem {

namespace {

void putMatrix(float out[16], const Mat4& m) {
  std::memcpy(out, &m.m[0][0], 16 * sizeof(float));
}

// The layout as the kernels read it: per sample x, y and the pair's bits; the samples in pair
// order.
void packLayout(const SampleLayout& L, Buffer& layout, Buffer& ids) {
  layout = Buffer(int(L.sampleCount()), 1, 3);
  for (size_t i = 0; i < L.sampleCount(); ++i) {
    const uint32_t pair = L.pair[i];
    layout.data[3 * i] = L.pos[i].x;
    layout.data[3 * i + 1] = L.pos[i].y;
    std::memcpy(&layout.data[3 * i + 2], &pair, sizeof pair);
  }
  ids = Buffer(int(L.ids.size()), 1, 1);
  std::memcpy(ids.data.data(), L.ids.data(), L.ids.size() * sizeof(uint32_t));
}

}  // namespace

void InterleavedRTPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const InterleavedSettings& s = settings();
  const Pairs p = framePairs(ctx);
  const TileShape& shape = p.tiles->shape;
  const int n = s.samples;
  const bool whittedShading = s.shading == InterleavedSettings::Shading::Whitted;
  InterleavedArgs a{};
  const ShadowMaps* maps =
      whittedShading ? shadowMapsFor(ctx, *this, s.whitted, nullptr, true) : nullptr;
  a.shadowMaps = maps ? gpuShadowMaps(ctx, *maps) : 0;
  const WhittedSettings ws = s.whitted.settings();
  a.whittedFlags = gpuWhittedFlags(ws, maps != nullptr);
  a.maxDepth = ws.maxDepth;
  a.importanceCutoff = ws.importanceCutoff;
  a.shadowCull = ws.shadowCull;
  a.flags = (whittedShading ? TD_IL_WHITTED : 0u) | (s.time() ? TD_IL_TIME : 0u);
  a.hdr = ctx.deviceOutput(*this, Slots::hdr);
  a.velocity = ctx.deviceOutput(*this, Slots::velocity);
  a.depth = ctx.deviceOutput(*this, Slots::viewDepth);
  a.motion = ctx.deviceOutputIfConsumed(*this, Slots::motion);
  a.mask =
      ctx.optionalInput(*this, Slots::sampleMask) ? ctx.deviceInput(*this, Slots::sampleMask) : 0;
  a.reach = int(std::ceil(s.filterRadius - 0.5f));
  a.radius = s.filterRadius;
  // The filter's 1D weight, tabulated as InterleavedPass::resolve tabulates it.
  std::vector<float> table(TD_IL_TABLE + 2);
  const bool bh = s.filter == InterleavedSettings::Filter::BlackmanHarris;
  for (int i = 0; i <= TD_IL_TABLE + 1; ++i)
    table[size_t(i)] = i > TD_IL_TABLE ? 0.0f : bh ? blackmanHarris(float(i) / TD_IL_TABLE) : 1.0f;
  a.weights = gpu.constants(table.data(), table.size() * sizeof(float));
  a.toTable = float(TD_IL_TABLE) / s.filterRadius;
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
  // A shutter whose objects move: the scene at each pair's time (else the frame's, once).
  bool moving = false;
  for (const FrameObject& fo : ctx.frame.objects) moving |= fo.stepPositions.size() >= 2;
  moving = moving && s.time();
  const GpuKernel& k = gpu.kernel("interleaved", kInterleavedSpv, sizeof(kInterleavedSpv) / 4,
                                  sizeof(InterleavedPush));
  const auto rows = [](uint64_t entries) { return uint32_t((entries + 4095) / 4096); };
  for (const View& v : ctx.views) {
    const int W = v.width(), H = v.height();
    const SampleLayout& L = layoutFor(ctx, *p.tiles, W, H);
    if (layoutVersion() != packedVersion_) {
      packLayout(L, layoutBuffer_, idsBuffer_);
      packedVersion_ = layoutVersion();
      gpu.hostWrote(name() + ":layout");
      gpu.hostWrote(name() + ":ids");
    }
    gpu.upload(name() + ":layout", layoutBuffer_);
    gpu.upload(name() + ":ids", idsBuffer_);
    a.sampleData = gpu.read(name() + ":layout").address;
    a.ids = gpu.read(name() + ":ids").address;
    const size_t samples = L.sampleCount();
    a.colour = gpu.scratch(name() + ":colour", samples * 3 * sizeof(float)).address;
    a.position = gpu.scratch(name() + ":position", samples * 3 * sizeof(float)).address;
    a.object = gpu.scratch(name() + ":object", samples * sizeof(uint32_t)).address;
    a.viewX = v.x, a.viewY = v.y, a.width = W, a.height = H;
    a.spread = ctx.pixelSpread(v) / std::sqrt(float(s.spp)) * s.textureFootprint;
    const std::vector<Camera> cams = pairCameras(v, p);
    const MotionCarry mc = motionCarry(ctx, p.taus, v, a.motion != 0);
    std::vector<IlPair> pairs(static_cast<size_t>(n));
    std::vector<IlCarry> carry(size_t(n) * animated.size());
    for (size_t j = 0; j < size_t(n); ++j) {
      pairs[j].camera = gpuCamera(cams[j], 0.0f);
      pairs[j].tau = p.taus[j];
      if (a.motion) {
        putMatrix(pairs[j].nowViewProj, mc.nowCams[j].viewProjUnjittered);
        putMatrix(pairs[j].prevViewProj, mc.prevCams[j].viewProjUnjittered);
      }
      for (size_t o = 0; o < ctx.scene->objects.size(); ++o) {
        IlCarry& c = carry[j * animated.size() + o];
        putMatrix(c.open, mc.carry[j][o].first);
        putMatrix(c.close, mc.carry[j][o].second);
        putMatrix(c.prev, mc.carryPrev[j][o]);
      }
    }
    a.pairs = gpu.constants(pairs.data(), pairs.size() * sizeof(IlPair));
    a.carry = gpu.constants(carry.data(), carry.size() * sizeof(IlCarry));
    putMatrix(a.openViewProj, v.camera.viewProjUnjittered);
    putMatrix(a.closeViewProj, v.shutterCamera.viewProjUnjittered);
    for (int j = 0; j < n; ++j) {
      a.scene = gpu.scene(moving ? ctx.frame.at(p.taus[size_t(j)]) : ctx.frame).sceneAddress();
      const uint32_t begin = L.passBegin(j), count = L.passEnd(j) - begin;
      InterleavedPush push{gpu.constants(&a, sizeof a), TD_IL_SHADE, uint32_t(j), begin, count};
      if (count > 0) gpu.dispatchInterruptibly(k, 64, rows(count), &push);
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
}

}  // namespace tandem
