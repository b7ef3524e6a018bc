// Emissive meshes -> punctual lights, for pipelines without area lights.
#include <cmath>

#include "scene/loaders.h"

namespace tandem {

int addLightsForEmissiveMeshes(Scene& s) {
  int added = 0;
  for (const Object& o : s.objects) {
    const Material& m = s.materials[o.material];
    if (maxComponent(m.emission) <= 0.0f) continue;
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
    float lum = maxComponent(m.emission);
    l.color = m.emission / lum;
    // Planar when the summed normal is (almost) as long as the total area.
    bool planar = length(normalSum) > 0.99 * area;
    if (planar) {
      // Lambertian emitter: I(theta) = Le * A * cos(theta) over the front hemisphere.
      l.type = LightType::Spot;
      l.direction = normalize(normalSum);
      l.position = centroid + l.direction * 1e-3f;  // just off the surface it stands for
      l.intensity = lum * float(area);
      l.innerConeDeg = 90.0f;
      l.outerConeDeg = 90.0f;
      l.cosinePower = 1.0f;
    } else {
      // Same total power Phi = pi * Le * A spread evenly: I = Phi / (4 pi) = Le * A / 4.
      l.type = LightType::Point;
      l.position = centroid;
      l.intensity = lum * float(area) * 0.25f;
    }
    l.castsShadows = true;
    s.lights.push_back(l);
    ++added;
  }
  return added;
}

}  // namespace tandem
