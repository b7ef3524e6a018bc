#include "scene/material.h"

#include <algorithm>
#include <cmath>

namespace tandem {

BlinnPhongTerms fromMetallicRoughness(Vec3 base, float metal, float rough) {
  metal = std::clamp(metal, 0.0f, 1.0f);
  rough = std::clamp(rough, 0.0f, 1.0f);
  float alpha = std::max(rough * rough, 1e-3f);  // GGX alpha; Blinn-Phong n = 2 / alpha^2 - 2
  return {base * (1.0f - metal), lerp(Vec3(0.04f), base, metal),
          std::clamp(2.0f / (alpha * alpha) - 2.0f, 1.0f, 4096.0f), metal * (1.0f - rough)};
}

}  // namespace tandem
