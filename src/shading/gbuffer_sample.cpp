#include "shading/gbuffer_sample.h"

#include "shading/gbuffer_layout.h"
#include "shading/shade_batch.h"

namespace tandem {

const std::vector<BufferSlot>& gbufferSampleSlots() {
  static const std::vector<BufferSlot> slots = [] {
    std::vector<BufferSlot> s;
    for (const char* n : {"position", "normal", "geo_normal", "diffuse", "specular", "emission",
                          "ambient", "optical", "object_id", "material_id"})
      s.push_back(gbufferSlot(n));
    return s;
  }();
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
  using D = DiffuseChannels;
  using S = SpecularChannels;
  using O = OpticalChannels;
  s.diffuse = v3(g_.diffuse + D::kCount * i + D::kRgb);
  s.diffuseOpacity = g_.diffuse[D::kCount * i + D::kOpacity];
  s.specular = v3(g_.specular + S::kCount * i + S::kRgb);
  s.specularExponent = g_.specular[S::kCount * i + S::kExponent];
  s.emission = v3(g_.emission + 3 * i);
  s.ambient = v3(g_.ambient + 3 * i);
  s.reflectivity = g_.optical[O::kCount * i + O::kReflectivity];
  s.ior = g_.optical[O::kCount * i + O::kIor];
  s.opacity = g_.optical[O::kCount * i + O::kOpacity];
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
  put(F::DR, g_.diffuse + DiffuseChannels::kCount * i + DiffuseChannels::kRgb);
  put(F::SR, g_.specular + SpecularChannels::kCount * i + SpecularChannels::kRgb);
  b.f[F::EXP][lane] = g_.specular[SpecularChannels::kCount * i + SpecularChannels::kExponent];
  put(F::ER, g_.emission + 3 * i);
  put(F::AR, g_.ambient + 3 * i);
  return true;
}

}  // namespace tandem
