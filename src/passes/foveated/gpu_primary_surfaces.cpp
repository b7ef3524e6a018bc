#include "passes/foveated/gpu_primary_surfaces.h"

#include <vector>

#include "gpu/gpu_camera.h"
#include "passes/foveated/primary_surface.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

uint64_t gpuFoveatedViews(FrameContext& ctx) {
  std::vector<FoveatedView> views;
  for (const View& v : ctx.views) {
    FoveatedView g{};
    g.camera = gpuCamera(v.jitteredCamera, 0.0f);
    const Vec3 eye = v.camera.desc.position, fwd = v.camera.forward;
    g.eye[0] = eye.x, g.eye[1] = eye.y, g.eye[2] = eye.z;
    g.forward[0] = fwd.x, g.forward[1] = fwd.y, g.forward[2] = fwd.z;
    g.orthographic = v.camera.desc.projection == Projection::Perspective ? 0 : 1;
    g.x = v.x;
    g.y = v.y;
    g.width = v.width();
    g.height = v.height();
    views.push_back(g);
  }
  return ctx.gpu->constants(views.data(), views.size() * sizeof(FoveatedView));
}

uint64_t gpuEyeViews(FrameContext& ctx) {
  std::vector<EyeView> views;
  for (const View& v : ctx.views) {
    const Vec3 eye = v.camera.desc.position;
    views.push_back({{eye.x, eye.y, eye.z}, v.x, v.y, v.width(), v.height(), 0});
  }
  return ctx.gpu->constants(views.data(), views.size() * sizeof(EyeView));
}

GpuPrimarySurfaces gpuPrimarySurfaces(const FrameContext& ctx, const Pass& pass) {
  const char* const* s = PrimarySurfaces::kSlots;
  return {ctx.deviceInput(pass, s[0]), ctx.deviceInput(pass, s[1]), ctx.deviceInput(pass, s[2]),
          ctx.deviceInput(pass, s[3]), ctx.deviceInput(pass, s[4]), ctx.deviceInput(pass, s[5])};
}

}  // namespace tandem
