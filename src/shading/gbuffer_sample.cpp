#include "shading/gbuffer_sample.h"

#include "pipeline/frame_context.h"

namespace tandem {

const std::vector<BufferSlot>& gbufferSampleSlots() {
  static const std::vector<BufferSlot> slots = {
      {"position", 3}, {"normal", 3},  {"geo_normal", 3}, {"diffuse", 4},   {"specular", 4},
      {"emission", 3}, {"ambient", 3}, {"optical", 3},    {"object_id", 1}, {"material_id", 1}};
  return slots;
}

GBufferReader::GBufferReader(const FrameContext& ctx, const Pass& pass) {
  auto get = [&](const char* slot) { return ctx.input(pass.bufferName(slot)).data.data(); };
  position_ = get("position");
  normal_ = get("normal");
  geoNormal_ = get("geo_normal");
  diffuse_ = get("diffuse");
  specular_ = get("specular");
  emission_ = get("emission");
  ambient_ = get("ambient");
  optical_ = get("optical");
  objectId_ = get("object_id");
  materialId_ = get("material_id");
  width_ = ctx.width;
}

bool GBufferReader::read(int x, int y, SurfaceSample& s) const {
  size_t i = size_t(y) * width_ + x;
  if (objectId_[i] < 0) return false;
  auto v3 = [](const float* p) { return Vec3(p[0], p[1], p[2]); };
  s.position = v3(position_ + 3 * i);
  s.normal = v3(normal_ + 3 * i);
  s.geoNormal = v3(geoNormal_ + 3 * i);
  s.diffuse = v3(diffuse_ + 4 * i);
  s.diffuseOpacity = diffuse_[4 * i + 3];
  s.specular = v3(specular_ + 4 * i);
  s.specularExponent = specular_[4 * i + 3];
  s.emission = v3(emission_ + 3 * i);
  s.ambient = v3(ambient_ + 3 * i);
  s.reflectivity = optical_[3 * i];
  s.ior = optical_[3 * i + 1];
  s.opacity = optical_[3 * i + 2];
  s.object = int(objectId_[i]);
  s.material = int(materialId_[i]);
  return true;
}

}  // namespace tandem
