#include "pipeline/gpu_gbuffer.h"

#include <cstring>

#include "gpu/gpu_camera.h"
#include "pipeline/gpu_frame.h"
#include "raster/gbuffer.h"
#include "shading/gbuffer_sample.h"

namespace tandem {

namespace {
// Fields of GBufferTargets in gbufferLayout()'s order.
uint64_t* targetField(GBufferTargets& t, size_t i) {
  uint64_t* f[] = {&t.depth,    &t.position, &t.normal,  &t.geoNormal, &t.diffuse,    &t.specular,
                   &t.emission, &t.ambient,  &t.optical, &t.objectId,  &t.materialId, &t.motion};
  return f[i];
}
}  // namespace

uint64_t gbufferDeviceTargets(FrameContext& ctx, const Pass& pass) {
  GBufferTargets t{};
  const std::vector<BufferSlot>& slots = gbufferSlots();
  for (size_t i = 0; i < slots.size(); ++i) {
    const std::string& s = slots[i].slot;
    *targetField(t, i) = s == "depth" || s == "motion" ? ctx.deviceOutputIfConsumed(pass, s)
                                                       : ctx.deviceOutput(pass, s);
  }
  return ctx.gpu->constants(&t, sizeof t);
}

uint64_t gbufferDeviceTargetsIfConsumed(FrameContext& ctx, const Pass& pass) {
  GBufferTargets t{};
  const std::vector<BufferSlot>& slots = gbufferSlots();
  for (size_t i = 0; i < slots.size(); ++i)
    *targetField(t, i) = ctx.deviceOutputIfConsumed(pass, slots[i].slot);
  return ctx.gpu->constants(&t, sizeof t);
}

uint64_t gbufferDeviceSources(FrameContext& ctx, const Pass& pass) {
  GBufferTargets t{};
  const std::vector<BufferSlot>& slots = gbufferSlots();
  for (size_t i = 0; i < slots.size(); ++i)
    for (const BufferSlot& read : gbufferSampleSlots())
      if (read.slot == slots[i].slot) *targetField(t, i) = ctx.deviceInput(pass, read.slot);
  return ctx.gpu->constants(&t, sizeof t);
}

uint64_t gpuViewConstants(FrameContext& ctx, const View& v) {
  GpuView g{};
  g.camera = gpuCamera(v.jitteredCamera, ctx.pixelSpread(v));
  std::memcpy(g.viewProj, &v.camera.viewProjUnjittered.m[0][0], sizeof g.viewProj);
  std::memcpy(g.prevViewProj, &v.prevCamera.viewProjUnjittered.m[0][0], sizeof g.prevViewProj);
  const Camera& c = v.jitteredCamera;
  g.depthOrigin[0] = c.desc.position.x, g.depthOrigin[1] = c.desc.position.y;
  g.depthOrigin[2] = c.desc.position.z;
  g.farPlane = c.desc.farPlane;
  g.cameraMoved = v.cameraMoved ? 1 : 0;
  g.perspective = c.desc.projection == Projection::Perspective ? 1 : 0;
  return ctx.gpu->constants(&g, sizeof g);
}

uint64_t gpuObjectMotionConstants(FrameContext& ctx) {
  std::vector<GpuObjectMotion> m(std::max<size_t>(ctx.frame.objects.size(), 1));
  for (size_t o = 0; o < ctx.frame.objects.size(); ++o) {
    const FrameObject& fo = ctx.frame.objects[o];
    std::memcpy(m[o].worldToPrev, &fo.worldToPrev.m[0][0], sizeof m[o].worldToPrev);
    m[o].moved = fo.moved ? 1 : 0;
  }
  return ctx.gpu->constants(m.data(), m.size() * sizeof(GpuObjectMotion));
}

}  // namespace tandem
