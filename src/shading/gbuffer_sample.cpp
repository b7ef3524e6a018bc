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
  g_ = {p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9]};
}

bool GBufferReader::read(int x, int y, SurfaceSample& s) const {
  size_t i = size_t(y) * width_ + x;
  if (g_.objectId[i] < 0) return false;
  auto v3 = [](const float* p) { return Vec3(p[0], p[1], p[2]); };
  s.position = v3(g_.position + 3 * i);
  s.normal = v3(g_.normal + 3 * i);
  s.geoNormal = v3(g_.geoNormal + 3 * i);
  s.diffuse = v3(g_.diffuse + 4 * i);
  s.diffuseOpacity = g_.diffuse[4 * i + 3];
  s.specular = v3(g_.specular + 4 * i);
  s.specularExponent = g_.specular[4 * i + 3];
  s.emission = v3(g_.emission + 3 * i);
  s.ambient = v3(g_.ambient + 3 * i);
  s.reflectivity = g_.optical[3 * i];
  s.ior = g_.optical[3 * i + 1];
  s.opacity = g_.optical[3 * i + 2];
  s.object = int(g_.objectId[i]);
  s.material = int(g_.materialId[i]);
  return true;
}

bool GBufferReader::read(int x, int y, ShadeBatch& b, int lane) const {
  const size_t i = size_t(y) * width_ + x;
  if (g_.objectId[i] < 0) return false;
  using F = ShadeBatch;
  auto put = [&](int field, const float* p) {
    b.f[field][lane] = p[0];
    b.f[field + 1][lane] = p[1];
    b.f[field + 2][lane] = p[2];
  };
  put(F::PX, g_.position + 3 * i);
  put(F::NX, g_.normal + 3 * i);
  put(F::DR, g_.diffuse + 4 * i);
  put(F::SR, g_.specular + 4 * i);
  b.f[F::EXP][lane] = g_.specular[4 * i + 3];
  put(F::ER, g_.emission + 3 * i);
  put(F::AR, g_.ambient + 3 * i);
  return true;
}

}  // namespace tandem
