#include "scene/scene.h"

#include <cmath>

#include "core/error.h"

namespace tandem {

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const Object& o : objects) n += meshes[o.mesh].triangleCount();
  return n;
}

Bounds3 Scene::bounds(float t) const {
  Bounds3 b;
  for (const Object& o : objects) {
    Mat4 m = o.worldMatrix(t);
    for (const Vec3& p : meshes[o.mesh].positions) b.extend(m.transformPoint(p));
  }
  return b;
}

size_t Scene::memoryBytes() const {
  size_t n = 0;
  for (const Mesh& m : meshes) n += m.memoryBytes();
  for (const Texture& t : textures) {
    n += t.texels.data.size() * sizeof(float);
    for (const Texture::Level& l : t.levels) n += l.rgba.size();
  }
  n += materials.size() * sizeof(Material) + objects.size() * sizeof(Object) +
       lights.size() * sizeof(Light);
  return n;
}

Vec3 Scene::skyRadiance(Vec3 d) const {
  if (!skybox.hasFaces()) return skybox.color;
  // Cube-map lookup: pick the major axis, project onto that face (OpenGL convention).
  float ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  int face;
  float sc, tc, ma;
  if (ax >= ay && ax >= az) {
    face = d.x > 0 ? 0 : 1;
    ma = ax;
    sc = d.x > 0 ? -d.z : d.z;
    tc = -d.y;
  } else if (ay >= az) {
    face = d.y > 0 ? 2 : 3;
    ma = ay;
    sc = d.x;
    tc = d.y > 0 ? d.z : -d.z;
  } else {
    face = d.z > 0 ? 4 : 5;
    ma = az;
    sc = d.z > 0 ? d.x : -d.x;
    tc = -d.y;
  }
  if (!(ma > 0)) return skybox.color;
  Vec2 uv{0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)};
  return textures[skybox.faces[face]].sample(uv).xyz();
}

int Scene::addMaterial(const Material& m) {
  materials.push_back(m);
  return int(materials.size()) - 1;
}

int Scene::addTexture(Texture t) {
  if (t.levels.empty()) t.buildLevels();  // a texture made by hand has only its float texels
  textures.push_back(std::move(t));
  return int(textures.size()) - 1;
}

int Scene::addMesh(Mesh m) {
  completeMesh(m);
  meshes.push_back(std::move(m));
  return int(meshes.size()) - 1;
}

int Scene::addObject(std::string n, int mesh, int material, Transform xf) {
  Object o;
  o.name = std::move(n);
  o.mesh = mesh;
  o.material = material;
  o.local = xf;
  objects.push_back(std::move(o));
  return int(objects.size()) - 1;
}

void Scene::append(const Scene& other, const Mat4& xf, int materialOverride) {
  const int meshBase = int(meshes.size()), matBase = int(materials.size());
  const int texBase = int(textures.size());
  meshes.insert(meshes.end(), other.meshes.begin(), other.meshes.end());
  textures.insert(textures.end(), other.textures.begin(), other.textures.end());
  for (Material m : other.materials) {
    for (int* t : {&m.diffuseTexture, &m.emissionTexture, &m.specularTexture, &m.normalTexture,
                   &m.metallicRoughnessTexture})
      if (*t >= 0) *t += texBase;
    materials.push_back(m);
  }
  for (Object o : other.objects) {
    o.mesh += meshBase;
    o.material = materialOverride >= 0 ? materialOverride : o.material + matBase;
    o.parent = xf * o.parent;
    objects.push_back(std::move(o));
  }
  for (Light l : other.lights) {
    l.position = xf.transformPoint(l.position);
    l.direction = normalize(xf.transformVector(l.direction));
    lights.push_back(l);
  }
  stats.degenerateTriangles += other.stats.degenerateTriangles;
  stats.sources.insert(stats.sources.end(), other.stats.sources.begin(), other.stats.sources.end());
}

void validateScene(const Scene& s, const std::string& source) {
  for (size_t mi = 0; mi < s.meshes.size(); ++mi) {
    const Mesh& m = s.meshes[mi];
    std::string where = "mesh " + std::to_string(mi);
    if (m.indices.size() % 3) throw InputError(source, where, "index count not a multiple of 3");
    for (uint32_t i : m.indices)
      if (i >= m.positions.size())
        throw InputError(source, where,
                         "vertex index " + std::to_string(i) + " out of range (" +
                             std::to_string(m.positions.size()) + " vertices)");
    for (const Vec3& p : m.positions)
      if (!isFinite(p)) throw InputError(source, where, "vertex position is NaN or infinite");
  }
  for (size_t oi = 0; oi < s.objects.size(); ++oi) {
    const Object& o = s.objects[oi];
    if (o.mesh < 0 || o.mesh >= int(s.meshes.size()))
      throw InputError(source, "object '" + o.name + "'", "mesh index out of range");
    if (o.material < 0 || o.material >= int(s.materials.size()))
      throw InputError(source, "object '" + o.name + "'", "material index out of range");
  }
  for (const Material& m : s.materials)
    for (int t : {m.diffuseTexture, m.emissionTexture, m.specularTexture, m.normalTexture,
                  m.metallicRoughnessTexture})
      if (t >= int(s.textures.size()))
        throw InputError(source, "material '" + m.name + "'", "texture index out of range");
}

}  // namespace tandem
