// Emissive meshes -> punctual lights, for pipelines without area lights.
#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/loaders.h"

namespace tandem {

namespace {
// A very bright, large emitter's intensity is clamped to the largest float instead of becoming
// infinite (docs/scene-format.md).
float finiteIntensity(double intensity) {
  return float(std::min(intensity, double(std::numeric_limits<float>::max())));
}
}  // namespace

namespace {

// Mean linear colour of a texture's level 0: what an emission texture makes of the factor on
// average (a mostly black glow map is a faint light, not a lamp).
Vec3 meanColor(const Texture& t) {
  const Buffer& b = t.texels;
  if (b.pixelCount() == 0 || b.channels < 3) return Vec3(1.0f);
  double sum[3] = {0, 0, 0};
  for (size_t i = 0; i < b.pixelCount(); ++i)
    for (int k = 0; k < 3; ++k) sum[k] += b.data[i * size_t(b.channels) + size_t(k)];
  const double n = double(b.pixelCount());
  return Vec3(float(sum[0] / n), float(sum[1] / n), float(sum[2] / n));
}

}  // namespace

Vec3 meanEmission(const Scene& s, const Material& m) {
  if (m.emissionTexture < 0) return m.emission;
  return m.emission * meanColor(s.textures[size_t(m.emissionTexture)]);
}

int addLightsForEmissiveMeshes(Scene& s) {
  int added = 0;
  std::vector<Vec3> emission(s.materials.size());
  for (size_t i = 0; i < s.materials.size(); ++i)
    emission[i] =
        maxComponent(s.materials[i].emission) > 0 ? meanEmission(s, s.materials[i]) : Vec3(0.0f);
  for (const Object& o : s.objects) {
    const Vec3 le = emission[size_t(o.material)];
    if (maxComponent(le) <= 0.0f) continue;
    const Mesh& mesh = s.meshes[o.mesh];
    Mat4 w = o.worldMatrix(0.0f);
    double area = 0;
    Vec3 centroid(0.0f), normalSum(0.0f);
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      Vec3 a = w.transformPoint(mesh.positions[mesh.indices[3 * t]]);
      Vec3 b = w.transformPoint(mesh.positions[mesh.indices[3 * t + 1]]);
      Vec3 c = w.transformPoint(mesh.positions[mesh.indices[3 * t + 2]]);
      Vec3 n = cross(b - a, c - a) * 0.5f;  // area-weighted normal
      float ta = length(n);
      area += ta;
      centroid += (a + b + c) * (ta / 3.0f);
      normalSum += n;
    }
    if (area <= 0) continue;
    centroid = centroid / float(area);
    Light l;
    l.name = "emissive:" + o.name;
    l.fromEmissiveMesh = true;
    float lum = maxComponent(le);
    l.color = le / lum;
    // Planar when the summed normal is (almost) as long as the total area.
    bool planar = length(normalSum) > 0.99 * area;
    if (planar) {
      // Lambertian emitter: I(theta) = Le * A * cos(theta) over the front hemisphere.
      l.type = LightType::Spot;
      l.direction = normalize(normalSum);
      l.position = centroid + l.direction * 1e-3f;  // just off the surface it stands for
      l.intensity = finiteIntensity(double(lum) * area);
      l.innerConeDeg = 90.0f;
      l.outerConeDeg = 90.0f;
      l.cosinePower = 1.0f;
    } else {
      // Same total power Phi = pi * Le * A spread evenly: I = Phi / (4 pi) = Le * A / 4.
      l.type = LightType::Point;
      l.position = centroid;
      l.intensity = finiteIntensity(double(lum) * area * 0.25);
    }
    l.castsShadows = true;
    s.lights.push_back(l);
    ++added;
  }
  return added;
}

}  // namespace tandem
