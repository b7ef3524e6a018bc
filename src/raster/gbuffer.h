// The G-buffer (shading/gbuffer_layout.h: its targets and their channels): named frame buffers
// written by the raster and the ray-traced G-buffer passes alike, from the same SurfaceSample.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "core/buffer.h"
#include "scene/frame_scene.h"
#include "scene/view.h"
#include "shading/gbuffer_layout.h"
#include "shading/surface.h"

namespace tandem {

const std::vector<BufferSlot>& gbufferSlots();

// Raw pointers to every G-buffer target, fetched once per pass (never per pixel).
struct GBufferView {
  float *depth, *position, *normal, *geoNormal, *diffuse, *specular, *emission, *ambient, *optical,
      *objectId, *materialId, *motion;
  int width;

  // `target(slot)` gives the buffer of one of gbufferSlots(), `width` pixels wide; null for
  // `depth` or `motion` when nothing reads them (they are then not written: depth and motion
  // need not be computed, see wantsDepth() and wantsMotion()).
  static GBufferView create(const std::function<Buffer*(const BufferSlot&)>& target);
  bool wantsDepth() const { return depth != nullptr; }
  bool wantsMotion() const { return motion != nullptr; }
  // Inline: the raster resolve writes a sample still in registers.
  void write(int x, int y, const SurfaceSample& s, float d, Vec2 mv) {
    const size_t i = size_t(y) * size_t(width) + size_t(x);
    auto put3 = [](float* p, Vec3 v) { p[0] = v.x, p[1] = v.y, p[2] = v.z; };
    if (depth) depth[i] = d;
    put3(position + 3 * i, s.position);
    put3(normal + 3 * i, s.normal);
    put3(geoNormal + 3 * i, s.geoNormal);
    using D = DiffuseChannels;
    using S = SpecularChannels;
    using O = OpticalChannels;
    put3(diffuse + D::kCount * i + D::kRgb, s.diffuse);
    diffuse[D::kCount * i + D::kOpacity] = s.diffuseOpacity;
    put3(specular + S::kCount * i + S::kRgb, s.specular);
    specular[S::kCount * i + S::kExponent] = s.specularExponent;
    put3(emission + 3 * i, s.emission);
    put3(ambient + 3 * i, s.ambient);
    optical[O::kCount * i + O::kReflectivity] = s.reflectivity;
    optical[O::kCount * i + O::kIor] = s.ior;
    optical[O::kCount * i + O::kOpacity] = s.opacity;
    objectId[i] = float(s.object);
    materialId[i] = float(s.material);
    if (motion) motion[2 * i] = mv.x, motion[2 * i + 1] = mv.y;
  }
  void writeBackground(int x, int y, Vec2 motion);
};

// Screen-space motion of a surface point of `object` in `view`: where it is now minus where it was
// (unjittered cameras).
Vec2 motionVector(const FrameScene& fs, const View& view, int object, Vec3 worldPos);
// Homogeneous point -> pixel coordinates of camera c through vp; false behind the camera.
// (Components one by one: the point usually was just stored as three floats, and a wide load of
// it would stall.)
inline bool projectToPixel(const Mat4& vp, const Camera& c, Vec4 q, Vec2& px) {
  const float* m = &vp.m[0][0];
  const Vec4 h{m[0] * q.x + m[1] * q.y + m[2] * q.z + m[3] * q.w,
               m[4] * q.x + m[5] * q.y + m[6] * q.z + m[7] * q.w,
               m[8] * q.x + m[9] * q.y + m[10] * q.z + m[11] * q.w,
               m[12] * q.x + m[13] * q.y + m[14] * q.z + m[15] * q.w};
  if (h.w <= 1e-8f) return false;
  px = {(h.x / h.w * 0.5f + 0.5f) * c.width, (0.5f - h.y / h.w * 0.5f) * c.height};
  return true;
}

// The same for a point known to lie on the camera ray of pixel centre `pixel` (view-local pixel
// coordinates, centres at +0.5): where it is now needs no projection (the unjittered camera
// sees it at pixel + jitter), only where it was. Inline: the raster resolve calls it per pixel.
// Motion of the pixel centre `pixel` whose point was at `prev` (world space) last frame.
inline Vec2 reprojectedMotion(const View& view, Vec3 prev, Vec2 pixel) {
  Vec2 before;
  if (!projectToPixel(view.prevCamera.viewProjUnjittered, view.prevCamera, Vec4(prev, 1.0f),
                      before))
    return {0, 0};
  return pixel + view.jitter - before;
}
inline Vec2 motionVectorAtPixel(const FrameScene& fs, const View& view, int object, Vec3 p,
                                Vec2 pixel) {
  const FrameObject& fo = fs.objects[size_t(object)];
  if (!fo.moved && !view.cameraMoved) return {0, 0};
  return reprojectedMotion(view, fo.moved ? fo.worldToPrev.transformPoint(p) : p, pixel);
}
// Motion of the background seen along `dir` (a point at infinity: only camera rotation moves it).
Vec2 backgroundMotion(const View& view, Vec3 dir);

}  // namespace tandem
