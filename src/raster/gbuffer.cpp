#include "raster/gbuffer.h"

#include "pipeline/frame_context.h"

namespace tandem {

const std::vector<BufferSlot>& gbufferSlots() {
  static const std::vector<BufferSlot> slots = {
      {"depth", 1},   {"position", 3},  {"normal", 3},      {"geo_normal", 3},
      {"diffuse", 4}, {"specular", 4},  {"emission", 3},    {"ambient", 3},
      {"optical", 3}, {"object_id", 1}, {"material_id", 1}, {"motion", 2}};
  return slots;
}

GBufferView GBufferView::create(FrameContext& ctx, const Pass& pass) {
  auto get = [&](const char* slot, int c) {
    return ctx.output(pass.bufferName(slot), c).data.data();
  };
  GBufferView v;
  v.depth = get("depth", 1);
  v.position = get("position", 3);
  v.normal = get("normal", 3);
  v.geoNormal = get("geo_normal", 3);
  v.diffuse = get("diffuse", 4);
  v.specular = get("specular", 4);
  v.emission = get("emission", 3);
  v.ambient = get("ambient", 3);
  v.optical = get("optical", 3);
  v.objectId = get("object_id", 1);
  v.materialId = get("material_id", 1);
  v.motion = get("motion", 2);
  v.width = ctx.width;
  return v;
}

namespace {
inline void put3(float* p, Vec3 v) {
  p[0] = v.x;
  p[1] = v.y;
  p[2] = v.z;
}
}  // namespace

void GBufferView::write(int x, int y, const SurfaceSample& s, float d, Vec2 mv) {
  size_t i = size_t(y) * width + x;
  depth[i] = d;
  put3(position + 3 * i, s.position);
  put3(normal + 3 * i, s.normal);
  put3(geoNormal + 3 * i, s.geoNormal);
  put3(diffuse + 4 * i, s.diffuse);
  diffuse[4 * i + 3] = s.diffuseOpacity;
  put3(specular + 4 * i, s.specular);
  specular[4 * i + 3] = s.specularExponent;
  put3(emission + 3 * i, s.emission);
  put3(ambient + 3 * i, s.ambient);
  put3(optical + 3 * i, {s.reflectivity, s.ior, s.opacity});
  objectId[i] = float(s.object);
  materialId[i] = float(s.material);
  motion[2 * i] = mv.x;
  motion[2 * i + 1] = mv.y;
}

void GBufferView::writeBackground(int x, int y, Vec2 mv) {
  size_t i = size_t(y) * width + x;
  depth[i] = 0;
  put3(position + 3 * i, Vec3(0.0f));
  put3(normal + 3 * i, Vec3(0.0f));
  put3(geoNormal + 3 * i, Vec3(0.0f));
  for (int k = 0; k < 4; ++k) diffuse[4 * i + k] = specular[4 * i + k] = 0;
  put3(emission + 3 * i, Vec3(0.0f));
  put3(ambient + 3 * i, Vec3(0.0f));
  put3(optical + 3 * i, Vec3(0.0f));
  objectId[i] = -1;
  materialId[i] = -1;
  motion[2 * i] = mv.x;
  motion[2 * i + 1] = mv.y;
}

namespace {
// Homogeneous point -> pixel coordinates; false behind the camera.
bool toPixel(const Mat4& vp, const Camera& c, Vec4 q, Vec2& px) {
  Vec4 h = vp * q;
  if (h.w <= 1e-8f) return false;
  px = {(h.x / h.w * 0.5f + 0.5f) * c.width, (0.5f - h.y / h.w * 0.5f) * c.height};
  return true;
}

Vec2 screenMotion(const FrameContext& ctx, Vec4 now, Vec4 before) {
  Vec2 a, b;
  if (!toPixel(ctx.camera.viewProjUnjittered, ctx.camera, now, a) ||
      !toPixel(ctx.prevCamera.viewProjUnjittered, ctx.prevCamera, before, b))
    return {0, 0};
  return a - b;
}
}  // namespace

Vec2 motionVector(const FrameContext& ctx, int object, Vec3 p) {
  const FrameObject& fo = ctx.frame.objects[object];
  if (!fo.moved && !ctx.cameraMoved) return {0, 0};
  Vec3 prev = fo.moved ? fo.worldToPrev.transformPoint(p) : p;
  return screenMotion(ctx, Vec4(p, 1.0f), Vec4(prev, 1.0f));
}

Vec2 backgroundMotion(const FrameContext& ctx, Vec3 dir) {
  if (!ctx.cameraMoved || ctx.camera.desc.projection != Projection::Perspective) return {0, 0};
  return screenMotion(ctx, Vec4(dir, 0.0f), Vec4(dir, 0.0f));
}

}  // namespace tandem
