#include "shading/gbuffer_sample.h"

#include "shading/shade_batch.h"

namespace tandem {

const std::vector<BufferSlot>& gbufferSampleSlots() {
  using K = BufferKind;
  static const std::vector<BufferSlot> slots = {
      {"position", 3, K::Position}, {"normal", 3, K::Normal},     {"geo_normal", 3, K::Normal},
      {"diffuse", 4, K::Material},  {"specular", 4, K::Material}, {"emission", 3, K::Color},
      {"ambient", 3, K::Material},  {"optical", 3, K::Material},  {"object_id", 1, K::Id},
      {"material_id", 1, K::Id}};
  return slots;
}

GBufferReader::GBufferReader(const std::function<const Buffer&(const BufferSlot&)>& source) {
  const std::vector<BufferSlot>& s = gbufferSampleSlots();
  const float* p[10];
  for (size_t i = 0; i < 10; ++i) {
    const Buffer& b = source(s[i]);
    p[i] = b.data.data();
    width_ = b.width;
  }
  position_ = p[0];
  normal_ = p[1];
  geoNormal_ = p[2];
  diffuse_ = p[3];
  specular_ = p[4];
  emission_ = p[5];
  ambient_ = p[6];
  optical_ = p[7];
  objectId_ = p[8];
  materialId_ = p[9];
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

bool GBufferReader::read(int x, int y, ShadeBatch& b, int lane) const {
  const size_t i = size_t(y) * width_ + x;
  if (objectId_[i] < 0) return false;
  using F = ShadeBatch;
  auto put = [&](int field, const float* p) {
    b.f[field][lane] = p[0];
    b.f[field + 1][lane] = p[1];
    b.f[field + 2][lane] = p[2];
  };
  put(F::PX, position_ + 3 * i);
  put(F::NX, normal_ + 3 * i);
  put(F::DR, diffuse_ + 4 * i);
  put(F::SR, specular_ + 4 * i);
  b.f[F::EXP][lane] = specular_[4 * i + 3];
  put(F::ER, emission_ + 3 * i);
  put(F::AR, ambient_ + 3 * i);
  return true;
}

}  // namespace tandem
