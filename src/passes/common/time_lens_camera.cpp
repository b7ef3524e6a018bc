#include "passes/common/time_lens_camera.h"

#include "pipeline/frame_context.h"
#include "rt/reference_render.h"

namespace tandem {

Camera cameraForPair(const View& v, const TimeLensPair& p, bool time, bool lens, Vec2 jitter) {
  const Camera atTau = time ? cameraAtShutter(v.camera, v.shutterCamera, p.tau) : v.camera;
  const Vec2 lensPoint = lens ? atTau.lensPoint(p.u1, p.u2) : Vec2{0, 0};
  return Camera::make(atTau.desc, v.width(), v.height(), jitter, lensPoint);
}

}  // namespace tandem
