#include "shading/gbuffer_layout.h"

#include <stdexcept>

namespace tandem {

const std::vector<BufferSlot>& gbufferLayout() {
  using K = BufferKind;
  static const std::vector<BufferSlot> slots = {
      {"depth", 1, K::Depth},
      {"position", 3, K::Position},
      {"normal", 3, K::Normal},
      {"geo_normal", 3, K::Normal},
      BufferSlot{"diffuse", 0, K::Material}.named({"r", "g", "b", "opacity"}),
      BufferSlot{"specular", 0, K::Material}.named({"r", "g", "b", "exponent"}),
      {"emission", 3, K::Color},
      BufferSlot{"ambient", 0, K::Material}.named({"r", "g", "b"}),
      BufferSlot{"optical", 0, K::Material}.named({"reflectivity", "ior", "opacity"}),
      {"object_id", 1, K::Id},
      {"material_id", 1, K::Id},
      {"motion", 2, K::Motion}};
  return slots;
}

const BufferSlot& gbufferSlot(const std::string& slot) {
  for (const BufferSlot& s : gbufferLayout())
    if (s.slot == slot) return s;
  throw std::logic_error("no G-buffer target '" + slot + "'");
}

}  // namespace tandem
