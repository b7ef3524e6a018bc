// The one shading function in structure-of-arrays form: up to kMax surfaces shaded together by a
// Highway kernel (8 lanes on AVX2), the lights' loop outside the lanes. Deferred shading fills
// whole batches from the G-buffer; a single ray hit is a batch of one (shadeBlinnPhong), so
// raster pixels and ray hits run the same instructions.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shading/blinn_phong.h"

namespace tandem {

struct ShadeBatch {
  static constexpr int kMax = 16;
  enum Field {
    PX,
    PY,
    PZ,  // world position
    NX,
    NY,
    NZ,  // shading normal (unit)
    WX,
    WY,
    WZ,  // unit direction surface -> viewer
    DR,
    DG,
    DB,  // diffuse albedo
    SR,
    SG,
    SB,   // specular colour
    EXP,  // specular exponent
    ER,
    EG,
    EB,  // emission
    AR,
    AG,
    AB,  // ambient colour
    OR,
    OG,
    OB,  // output: reflected radiance
    kFields
  };

  int count = 0;  // surfaces in lanes [0, count); later lanes are never read
  // The lights to evaluate (indices into ShadingContext::lights); null: all of them. Deferred
  // shading leaves out lights that cannot reach any lane (cullLights).
  const uint32_t* lights = nullptr;
  size_t lightCount = 0;
  alignas(64) float f[kFields][kMax];

  // Inline: resolve passes fill lanes from a sample still in registers.
  void set(int lane, const SurfaceSample& s, Vec3 wo) {
    f[PX][lane] = s.position.x, f[PY][lane] = s.position.y, f[PZ][lane] = s.position.z;
    f[NX][lane] = s.normal.x, f[NY][lane] = s.normal.y, f[NZ][lane] = s.normal.z;
    f[WX][lane] = wo.x, f[WY][lane] = wo.y, f[WZ][lane] = wo.z;
    f[DR][lane] = s.diffuse.x, f[DG][lane] = s.diffuse.y, f[DB][lane] = s.diffuse.z;
    f[SR][lane] = s.specular.x, f[SG][lane] = s.specular.y, f[SB][lane] = s.specular.z;
    f[EXP][lane] = s.specularExponent;
    f[ER][lane] = s.emission.x, f[EG][lane] = s.emission.y, f[EB][lane] = s.emission.z;
    f[AR][lane] = s.ambient.x, f[AG][lane] = s.ambient.y, f[AB][lane] = s.ambient.z;
  }
  // Lane j's light-independent terms (emission + global ambient x ambient colour), as the kernel
  // sums them: what is left of its result when every light is blocked.
  Vec3 unlit(int j, Vec3 ambient) const {
    return {f[ER][j] + ambient.x * f[AR][j], f[EG][j] + ambient.y * f[AG][j],
            f[EB][j] + ambient.z * f[AB][j]};
  }
  Vec3 result(int lane) const { return {f[OR][lane], f[OG][lane], f[OB][lane]}; }
};

// Listing 8a's shadow value of lane j, shaded with each light weighted by how much of it is
// blocked (1 - visibility): 1 minus the light the occluders take away.
inline Vec3 shadowFromBlocked(const ShadeBatch& b, int j, Vec3 ambient) {
  return Vec3(1.0f) - (b.result(j) - b.unlit(j, ambient));
}

// Lists in `out`, ascending, the lights of `ctx` that may light a point of `box` (range and spot
// cone, tested on the box's bounding sphere; directional and hemisphere lights always). Exact: a
// light left out contributes exactly 0 there. Through ctx.cull when there is one, so the cost
// follows the lights near the box, not the scene's.
void lightsReaching(const ShadingContext& ctx, const Bounds3& box, std::vector<uint32_t>& out);

// lightsReaching for the box around b's lanes (`lanes` when the caller has it), with b.lights
// pointed at `out`.
void cullLights(ShadeBatch& b, const ShadingContext& ctx, std::vector<uint32_t>& out,
                const Bounds3* lanes = nullptr);

// Shades lanes [0, b.count). lightVisibility: null (all visible) or an RGB transmittance per
// light and lane at lightVisibility[(3 * light + channel) * visStride + lane].
void shadeBatch(ShadeBatch& b, const ShadingContext& ctx, const float* lightVisibility = nullptr,
                size_t visStride = ShadeBatch::kMax);

// A light's terms at a lane as shading weighs them: the BRDF colour (diffuse / pi plus the
// specular lobe, RGB) and the light's cosine-weighted irradiance (RGB).
constexpr size_t kLightTerms = 6;

// The same shading with no visibility (b's result: the unshadowed radiance), also writing each
// evaluated light's unshadowed luminance per lane to perLight[light * stride + lane] (>= 0; 0
// where the light does not reach). Culling of shadow queries weighs lights by it. `terms`
// (optional): each evaluated light's terms too, at terms[(kLightTerms * light + t) * stride +
// lane] (lights * kLightTerms * stride floats), for shadeFromTerms.
void lightContributions(ShadeBatch& b, const ShadingContext& ctx, float* perLight,
                        size_t stride = ShadeBatch::kMax, float* terms = nullptr);

// shadeBatch(b, ctx, lightVisibility, stride) for the lights b points at, all of which
// lightContributions evaluated into `terms` for the same lanes: the same result to the bit,
// without evaluating the lights again.
void shadeFromTerms(ShadeBatch& b, const ShadingContext& ctx, const float* terms,
                    const float* lightVisibility, size_t stride = ShadeBatch::kMax);

}  // namespace tandem
