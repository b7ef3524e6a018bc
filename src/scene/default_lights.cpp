#include "scene/default_lights.h"

#include "scene/loaders.h"

namespace tandem {

bool needsDefaultLights(const Scene& s) {
  for (const Light& l : s.lights)
    if (!l.fromEmissiveMesh) return false;
  // An emitter at least as bright as a white surface under the rig's sun is a lamp that lights
  // the model (a Cornell box's ceiling); dimmer ones are glow accents (a label, a screen).
  for (const Object& o : s.objects)
    if (maxComponent(meanEmission(s, s.materials[size_t(o.material)])) >= 1.0f) return false;
  return true;
}

void addDefaultLightRig(Scene& s, const CameraDesc& camera) {
  const Vec3 forward = normalize(camera.lookAt - camera.position);
  Vec3 right = cross(forward, camera.up);
  right = length(right) > 1e-6f ? normalize(right) : Vec3(1, 0, 0);
  const Vec3 up = normalize(cross(right, forward));
  auto sun = [&](const char* name, Vec3 toLight, float intensity, Vec3 color, bool shadows) {
    Light l;
    l.type = LightType::Directional;
    l.name = name;
    l.direction = -normalize(toLight);  // the direction light travels
    l.intensity = intensity;
    l.color = color;
    l.castsShadows = shadows;
    s.lights.push_back(l);
  };
  // Irradiances in W/m^2 as --sun-light takes them: the key sun alone brings a white diffuse
  // surface facing it to about mid-grey after ACES, the other two keep shadowed sides readable.
  sun("default-sun", -forward * 0.8f + up * 1.0f - right * 0.6f, 2.6f, Vec3(1.0f, 0.96f, 0.9f),
      true);
  sun("default-sky", Vec3(0, 1, 0) - forward * 0.1f, 0.6f, Vec3(0.75f, 0.85f, 1.0f), false);
  sun("default-fill", -forward * 0.6f + right * 0.8f - up * 0.1f, 0.45f, Vec3(1.0f, 0.95f, 0.9f),
      false);
  if (maxComponent(s.ambient) <= 0.0f) s.ambient = Vec3(0.04f, 0.045f, 0.05f);
  s.stats.defaultLightRig = true;
}

}  // namespace tandem
