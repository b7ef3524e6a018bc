#include "scene/gltf_draco.h"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include <cmath>

#include "core/error.h"

namespace tandem {

DracoPrimitive decodeDracoPrimitive(const unsigned char* data, size_t size,
                                    const std::map<std::string, std::pair<int, int>>& attributes,
                                    const std::string& path, const std::string& field) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    throw InputError(
        path, field,
        std::string("Draco stream does not decode: ") + decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh>& mesh = decoded.value();
  if (!mesh) throw InputError(path, field, "Draco stream holds no mesh");
  DracoPrimitive out;
  out.points = mesh->num_points();
  if (out.points > (size_t(1) << 28)) throw InputError(path, field, "absurd Draco point count");
  out.indices.reserve(size_t(mesh->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh->face(f)[k].value();
      if (v >= out.points) throw InputError(path, field, "Draco face index out of range");
      out.indices.push_back(v);
    }
  for (const auto& [name, idComps] : attributes) {
    const auto [id, comps] = idComps;
    const draco::PointAttribute* a = id >= 0 ? mesh->GetAttributeByUniqueId(uint32_t(id)) : nullptr;
    if (!a)
      throw InputError(path, field + "." + name,
                       "Draco attribute id " + std::to_string(id) + " is not in the stream");
    if (a->num_components() < comps)
      throw InputError(path, field + "." + name,
                       "Draco attribute has " + std::to_string(int(a->num_components())) +
                           " components, " + std::to_string(comps) + " needed");
    std::vector<float>& values = out.attributes[name];
    values.resize(out.points * size_t(comps));
    float v[4] = {0, 0, 0, 0};
    for (draco::PointIndex p(0); p < mesh->num_points(); ++p) {
      const draco::AttributeValueIndex vi = a->mapped_index(p);
      if (vi.value() >= a->size() || !a->ConvertValue<float>(vi, int8_t(comps), v))
        throw InputError(path, field + "." + name, "Draco attribute value does not decode");
      for (int k = 0; k < comps; ++k) {
        if (!std::isfinite(v[k]))
          throw InputError(path, field + "." + name, "value is NaN or infinite");
        values[size_t(p.value()) * size_t(comps) + size_t(k)] = v[k];
      }
    }
  }
  return out;
}

}  // namespace tandem
