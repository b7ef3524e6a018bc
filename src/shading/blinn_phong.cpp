#include "shading/blinn_phong.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/scene.h"
#include "shading/light_cull_grid.h"
#include "shading/shade_batch.h"

namespace tandem {

namespace {
float smoothstep(float e0, float e1, float x) {
  if (e1 <= e0) return x >= e0 ? 1.0f : 0.0f;
  float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}
}  // namespace

PreparedLight PreparedLight::from(const Light& l) {
  PreparedLight p;
  p.type = l.type;
  p.power = l.color * l.intensity;
  p.position = l.position;
  p.direction = l.direction;
  p.attConstant = l.attConstant;
  p.attLinear = l.attLinear;
  p.attQuadratic = l.attQuadratic;
  p.range = l.range;
  p.cosOuter = std::cos(radians(l.outerConeDeg));
  p.cosInner = std::cos(radians(l.innerConeDeg));
  p.outerAngle = std::acos(std::clamp(p.cosOuter, -1.0f, 1.0f));
  p.cosinePower = l.cosinePower;
  p.hemisphere = l.outerConeDeg >= 90.0f && l.innerConeDeg >= 90.0f;
  return p;
}

ShadingContext ShadingContext::from(const Scene& scene) {
  ShadingContext c;
  c.ambient = scene.ambient;
  c.lights.reserve(scene.lights.size());
  for (const Light& l : scene.lights) c.lights.push_back(PreparedLight::from(l));
  c.cull = LightCullGrid::build(c.lights);
  return c;
}

LightSample sampleLight(const PreparedLight& l, Vec3 p) {
  LightSample s;
  if (l.type == LightType::Directional) {
    s.wi = -l.direction;
    s.distance = std::numeric_limits<float>::infinity();
    s.radiance = l.power;
    return s;
  }
  Vec3 d = l.position - p;
  float dist2 = dot(d, d);
  float dist = std::sqrt(dist2);
  s.wi = dist > 0 ? d / dist : Vec3(0, 1, 0);
  s.distance = dist;
  if (l.range > 0 && dist > l.range) {
    s.radiance = Vec3(0.0f);
    return s;
  }
  float att = 1.0f / std::max(l.attConstant + l.attLinear * dist + l.attQuadratic * dist2, 1e-8f);
  if (l.type == LightType::Spot) {
    float cosTheta = dot(-s.wi, l.direction);
    float cone =
        l.hemisphere ? (cosTheta > 0 ? 1.0f : 0.0f) : smoothstep(l.cosOuter, l.cosInner, cosTheta);
    if (l.cosinePower > 0) cone *= std::pow(std::max(cosTheta, 0.0f), l.cosinePower);
    att *= cone;
  }
  s.radiance = l.power * att;
  return s;
}

Vec3 shadeBlinnPhong(const SurfaceSample& s, Vec3 wo, const ShadingContext& ctx,
                     const Vec3* lightVisibility) {
  // A batch of one: the kernel deferred shading runs 8 lanes at a time.
  ShadeBatch b;
  b.count = 1;
  b.set(0, s, wo);
  // With many lights, only those that reach the point (the rest add exactly 0).
  thread_local std::vector<uint32_t> reaching;
  if (ctx.cull) cullLights(b, ctx, reaching);
  shadeBatch(b, ctx, lightVisibility ? &lightVisibility[0].x : nullptr, 1);
  return b.result(0);
}

Vec3 shadeBlinnPhong(const SurfaceSample& s, Vec3 wo, const Scene& scene,
                     const Vec3* lightVisibility) {
  return shadeBlinnPhong(s, wo, ShadingContext::from(scene), lightVisibility);
}

}  // namespace tandem
