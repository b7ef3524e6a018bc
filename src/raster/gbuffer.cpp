#include "raster/gbuffer.h"

#include "core/error.h"

namespace tandem {

const std::vector<BufferSlot>& gbufferSlots() {
  return gbufferLayout();
}

GBufferView GBufferView::create(const std::function<Buffer*(const BufferSlot&)>& target) {
  const std::vector<BufferSlot>& s = gbufferSlots();
  float* p[12];
  int width = 0;
  for (size_t i = 0; i < 12; ++i) {
    Buffer* b = target(s[i]);
    TANDEM_ASSERT(b || s[i].slot == "depth" || s[i].slot == "motion");
    p[i] = b ? b->data.data() : nullptr;
    if (b) width = b->width;
  }
  return {p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9], p[10], p[11], width};
}

void GBufferView::writeBackground(int x, int y, Vec2 mv) {
  size_t i = size_t(y) * width + x;
  if (depth) depth[i] = 0;
  auto put3 = [](float* p, Vec3 v) { p[0] = v.x, p[1] = v.y, p[2] = v.z; };
  put3(position + 3 * i, Vec3(0.0f));
  put3(normal + 3 * i, Vec3(0.0f));
  put3(geoNormal + 3 * i, Vec3(0.0f));
  for (int k = 0; k < 4; ++k) diffuse[4 * i + k] = specular[4 * i + k] = 0;
  put3(emission + 3 * i, Vec3(0.0f));
  put3(ambient + 3 * i, Vec3(0.0f));
  put3(optical + 3 * i, Vec3(0.0f));
  objectId[i] = -1;
  materialId[i] = -1;
  if (motion) motion[2 * i] = mv.x, motion[2 * i + 1] = mv.y;
}

namespace {
Vec2 screenMotion(const View& v, Vec4 now, Vec4 before) {
  Vec2 a, b;
  if (!projectToPixel(v.camera.viewProjUnjittered, v.camera, now, a) ||
      !projectToPixel(v.prevCamera.viewProjUnjittered, v.prevCamera, before, b))
    return {0, 0};
  return a - b;
}
}  // namespace

Vec2 motionVector(const FrameScene& fs, const View& view, int object, Vec3 p) {
  const FrameObject& fo = fs.objects[size_t(object)];
  if (!fo.moved && !view.cameraMoved) return {0, 0};
  Vec3 prev = fo.moved ? fo.worldToPrev.transformPoint(p) : p;
  return screenMotion(view, Vec4(p, 1.0f), Vec4(prev, 1.0f));
}

Vec2 backgroundMotion(const View& view, Vec3 dir) {
  if (!view.cameraMoved || view.camera.desc.projection != Projection::Perspective) return {0, 0};
  return screenMotion(view, Vec4(dir, 0.0f), Vec4(dir, 0.0f));
}

}  // namespace tandem
