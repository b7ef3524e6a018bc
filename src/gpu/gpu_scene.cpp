#include "gpu/gpu_scene.h"

#include <cmath>
#include <cstring>

#include "core/color.h"
#include "gpu/gpu_bvh.h"
#include "shading/blinn_phong.h"

namespace tandem {

namespace {
void put(float* out, Vec3 v) {
  out[0] = v.x, out[1] = v.y, out[2] = v.z;
}

GpuMaterial gpuMaterial(const Material& m) {
  GpuMaterial g{};
  put(g.emission, m.emission);
  put(g.ambient, m.ambient);
  put(g.diffuse, m.diffuse);
  g.diffuseOpacity = m.diffuseOpacity;
  put(g.specular, m.specular);
  g.specularExponent = m.specularExponent;
  g.reflectivity = m.reflectivity;
  g.ior = m.ior;
  g.opacity = m.opacity;
  put(g.transmissionFilter, m.transmissionFilter);
  g.tiling[0] = m.tiling.x, g.tiling[1] = m.tiling.y;
  g.offset[0] = m.offset.x, g.offset[1] = m.offset.y;
  g.uvCos = std::cos(m.uvRotation);  // as Material::transformUv computes them
  g.uvSin = std::sin(m.uvRotation);
  g.alphaCutoff = m.alphaCutoff;
  g.normalScale = m.normalScale;
  g.occlusionStrength = m.occlusionStrength;
  put(g.baseColor, m.baseColor);
  g.metallic = m.metallic;
  g.roughness = m.roughness;
  g.diffuseTexture = m.diffuseTexture;
  g.emissionTexture = m.emissionTexture;
  g.specularTexture = m.specularTexture;
  g.normalTexture = m.normalTexture;
  g.metallicRoughnessTexture = m.metallicRoughnessTexture;
  g.occlusionTexture = m.occlusionTexture;
  g.flags = (m.castsShadows ? TD_MAT_CASTS_SHADOWS : 0u) |
            (m.doubleSided ? TD_MAT_DOUBLE_SIDED : 0u) |
            (m.alphaMode == AlphaMode::Mask ? TD_MAT_ALPHA_MASK : 0u) |
            (m.alphaMode == AlphaMode::Blend ? TD_MAT_ALPHA_BLEND : 0u) |
            (m.uvRotation != 0.0f ? TD_MAT_UV_ROTATION : 0u);
  return g;
}

GpuLight gpuLight(const Light& light) {
  const PreparedLight l = PreparedLight::from(light);
  GpuLight g{};
  g.type = uint32_t(l.type);
  g.castsShadows = light.castsShadows ? 1 : 0;
  g.hemisphere = l.hemisphere ? 1 : 0;
  put(g.power, l.power);
  g.range = l.range;
  put(g.position, l.position);
  g.attConstant = l.attConstant;
  put(g.direction, l.direction);
  g.attLinear = l.attLinear;
  g.attQuadratic = l.attQuadratic;
  g.cosOuter = l.cosOuter;
  g.cosInner = l.cosInner;
  g.cosinePower = l.cosinePower;
  return g;
}

// The time steps a moving object keeps on the device (0: it stands still).
uint32_t motionSteps(const FrameObject& o) {
  return o.stepPositions.size() >= 2 ? uint32_t(o.stepPositions.size()) : 0;
}

// An object's positions and those of its time steps (FrameObject), one after the other.
std::vector<Vec3> geometryOf(const FrameObject& o) {
  std::vector<Vec3> all = o.positions;
  if (motionSteps(o))
    for (const std::vector<Vec3>& step : o.stepPositions)
      all.insert(all.end(), step.begin(), step.end());
  return all;
}

// Whether `built` (geometryOf when the BVH was built) is the object's geometry now, compared in
// place: no copy of the objects that did not move.
bool sameGeometry(const std::vector<Vec3>& built, const FrameObject& o) {
  size_t size = o.positions.size(), at = 0;
  if (motionSteps(o))
    for (const std::vector<Vec3>& step : o.stepPositions) size += step.size();
  if (built.size() != size) return false;
  const auto same = [&](const std::vector<Vec3>& part) {
    const bool equal = std::memcmp(built.data() + at, part.data(), part.size() * sizeof(Vec3)) == 0;
    at += part.size();
    return equal;
  };
  if (!same(o.positions)) return false;
  if (motionSteps(o))
    for (const std::vector<Vec3>& step : o.stepPositions)
      if (!same(step)) return false;
  return true;
}

// Leaf-order triangles at the frame's positions and at each time step.
void leafTriangles(const Mesh& mesh, const FrameObject& o, const std::vector<uint32_t>& prims,
                   std::vector<float>& triangles, std::vector<float>& stepTriangles) {
  triangles.resize(prims.size() * 9);
  const size_t steps = motionSteps(o);
  stepTriangles.resize(prims.size() * 9 * steps);
  for (size_t i = 0; i < prims.size(); ++i)
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * size_t(prims[i]) + k];
      std::memcpy(&triangles[9 * i + 3 * k], &o.positions[v], sizeof(Vec3));
      for (size_t s = 0; s < steps; ++s)
        std::memcpy(&stepTriangles[9 * (i * steps + s) + 3 * k], &o.stepPositions[s][v],
                    sizeof(Vec3));
    }
}
}  // namespace

GpuScene::~GpuScene() {
  for (GpuBuffer* b :
       {&nodes_,   &triangles_,     &prims_,       &roots_,   &motion_,   &motionTriangles_,
        &staging_, &materials_,     &textures_,    &levels_,  &texels_,   &lights_,
        &decode_,  &objectsBuf_,    &positions_,   &normals_, &tangents_, &uvs_,
        &indices_, &stepPositions_, &stepNormals_, &args_})
    memory_.release(*b);
}

GpuScene::ObjectBvh GpuScene::buildObject(const Scene& scene, const FrameObject& o, size_t index) {
  const Mesh& mesh = scene.meshes[size_t(scene.objects[index].mesh)];
  const size_t n = mesh.triangleCount();
  std::vector<Bounds3> boxes(n);
  for (size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + size_t(k)];
      boxes[t].extend(o.positions[v]);
      if (motionSteps(o))  // between steps a vertex stays inside the box of both
        for (const std::vector<Vec3>& step : o.stepPositions) boxes[t].extend(step[v]);
    }
  BvhBuild b = buildBvh(boxes);
  ObjectBvh out;
  out.nodes = std::move(b.nodes);
  out.prims = std::move(b.items);
  out.steps = motionSteps(o);
  leafTriangles(mesh, o, out.prims, out.triangles, out.stepTriangles);
  for (const Bounds3& box : boxes) out.bounds.extend(box);
  return out;
}

void GpuScene::refitObject(ObjectBvh& ob, const Scene& scene, const FrameObject& o, size_t index) {
  const Mesh& mesh = scene.meshes[size_t(scene.objects[index].mesh)];
  ob.steps = motionSteps(o);
  leafTriangles(mesh, o, ob.prims, ob.triangles, ob.stepTriangles);
  auto extendByTriangle = [&](Bounds3& b, size_t t) {
    for (size_t k = 0; k < 3; ++k)
      b.extend({ob.triangles[9 * t + 3 * k], ob.triangles[9 * t + 3 * k + 1],
                ob.triangles[9 * t + 3 * k + 2]});
    for (size_t s = 0; s < ob.steps; ++s)
      for (size_t k = 0; k < 3; ++k) {
        const float* p = &ob.stepTriangles[9 * (t * ob.steps + s) + 3 * k];
        b.extend({p[0], p[1], p[2]});
      }
  };
  // Children always follow their parent (buildBvh's order): from the last node back, every
  // child's box is final before its parent's is drawn around it.
  for (size_t n = ob.nodes.size(); n-- > 0;) {
    BvhNode& node = ob.nodes[n];
    if (node.lox > node.hix) continue;  // an empty slot stays empty
    Bounds3 b;
    if (node.count) {
      for (size_t t = node.a; t < node.a + node.count; ++t) extendByTriangle(b, t);
    } else {
      for (size_t c = node.a; c < node.a + 2; ++c) {
        const BvhNode& k = ob.nodes[c];
        if (k.lox <= k.hix) b.extend(Bounds3{{k.lox, k.loy, k.loz}, {k.hix, k.hiy, k.hiz}});
      }
    }
    node.lox = b.lo.x, node.loy = b.lo.y, node.loz = b.lo.z;
    node.hix = b.hi.x, node.hiy = b.hi.y, node.hiz = b.hi.z;
  }
  ob.bounds = Bounds3{{ob.nodes[0].lox, ob.nodes[0].loy, ob.nodes[0].loz},
                      {ob.nodes[0].hix, ob.nodes[0].hiy, ob.nodes[0].hiz}};
}

void GpuScene::update(const FrameScene& fs, GpuCommands& cmd) {
  if (current(fs)) return;
  const Scene& scene = *fs.scene;
  const bool fresh = fs.scene != scene_ || objects_.size() != fs.objects.size();
  objects_.resize(fs.objects.size());
  built_.resize(fs.objects.size());
  for (size_t o = 0; o < fs.objects.size(); ++o) {
    const FrameObject& fo = fs.objects[o];
    if (!fresh && sameGeometry(built_[o], fo)) continue;  // only what moved
    std::vector<Vec3> geometry = geometryOf(fo);
    // A BVH built for these triangles is refitted (its tree kept, its boxes redrawn around where
    // the triangles are now): cheaper than a build, and rigid motion barely loosens the boxes.
    if (!fresh && built_[o].size() == geometry.size())
      refitObject(objects_[o], scene, fo, o);
    else
      objects_[o] = buildObject(scene, fo, o);
    built_[o] = std::move(geometry);
  }
  scene_ = fs.scene;
  version_ = fs.geometryVersion;
  upload(cmd, fresh, fs);
}

GpuBuffer& GpuScene::ensure(GpuBuffer& b, size_t bytes) {
  if (b && b.size < bytes) memory_.release(b);
  if (!b) b = memory_.allocate(bytes, MemoryUse::Device);
  return b;
}

void GpuScene::upload(GpuCommands& cmd, bool sceneChanged, const FrameScene& fs) {
  // One array of nodes (each object's, offset, then the top level's), one of triangles.
  std::vector<BvhNode> nodes;
  std::vector<float> tris, stepTris;
  std::vector<uint32_t> prims, roots(objects_.size());
  std::vector<ObjectMotion> motion(objects_.size());
  std::vector<Bounds3> boxes(objects_.size());
  for (size_t o = 0; o < objects_.size(); ++o) {
    const ObjectBvh& ob = objects_[o];
    const uint32_t nodeBase = uint32_t(nodes.size()), triBase = uint32_t(prims.size());
    roots[o] = nodeBase;
    motion[o] = {ob.steps, triBase, uint32_t(stepTris.size() / 9), 0};
    stepTris.insert(stepTris.end(), ob.stepTriangles.begin(), ob.stepTriangles.end());
    for (BvhNode n : ob.nodes) {
      n.a += n.count ? triBase : nodeBase;
      nodes.push_back(n);
    }
    tris.insert(tris.end(), ob.triangles.begin(), ob.triangles.end());
    prims.insert(prims.end(), ob.prims.begin(), ob.prims.end());
    boxes[o] = ob.bounds;
  }
  BvhBuild top = buildBvh(boxes);
  topRoot_ = uint32_t(nodes.size());
  for (BvhNode n : top.nodes) {
    if (n.count == 0) n.a += topRoot_;
    nodes.push_back(n);
  }
  triangleCount_ = prims.size();
  // Layout of `roots`: per object its root node, then the top level's leaf order (object ids).
  const uint32_t listBase = uint32_t(roots.size());
  for (size_t i = size_t(topRoot_); i < nodes.size(); ++i)
    if (nodes[i].count) nodes[i].a += listBase;
  roots.insert(roots.end(), top.items.begin(), top.items.end());

  Staging st;
  stage(st, nodes_, nodes.data(), nodes.size() * sizeof(BvhNode));
  stage(st, triangles_, tris.data(), tris.size() * 4);
  stage(st, prims_, prims.data(), prims.size() * 4);
  stage(st, roots_, roots.data(), roots.size() * 4);
  stage(st, motion_, motion.data(), motion.size() * sizeof(ObjectMotion));
  stage(st, motionTriangles_, stepTris.data(), stepTris.size() * 4);
  stageShading(st, sceneChanged, fs);
  record(st, cmd);
}

void GpuScene::record(const Staging& st, GpuCommands& cmd) {
  size_t total = 0;
  for (const Staging::Piece& p : st.pieces) total += p.bytes.size();
  if (staging_ && staging_.size < total) memory_.release(staging_);
  if (!staging_) staging_ = memory_.allocate(std::max<size_t>(total, 16), MemoryUse::Upload);
  cmd.begin();
  size_t at = 0;
  for (const Staging::Piece& p : st.pieces) {
    if (p.bytes.empty()) continue;
    std::memcpy(static_cast<char*>(staging_.mapped) + at, p.bytes.data(), p.bytes.size());
    cmd.copy(staging_, *p.dst, p.bytes.size(), at, 0);
    at += p.bytes.size();
  }
  cmd.submit();
}

void GpuScene::stageShading(Staging& st, bool sceneChanged, const FrameScene& fs) {
  const Scene& scene = *fs.scene;
  if (sceneChanged) {
    std::vector<GpuMaterial> mats;
    for (const Material& m : scene.materials) mats.push_back(gpuMaterial(m));
    std::vector<GpuTexture> texs;
    std::vector<GpuTextureLevel> levels;
    std::vector<uint32_t> texels;
    for (const Texture& t : scene.textures) {
      GpuTexture g{};
      g.firstLevel = uint32_t(levels.size());
      g.levels = uint32_t(t.levels.size());
      g.wrapS = uint32_t(t.wrapS);
      g.wrapT = uint32_t(t.wrapT);
      g.srgb = t.srgb ? 1 : 0;
      g.size = t.levels.empty() ? 0 : uint32_t(std::max(t.levels[0].width, t.levels[0].height));
      for (const Texture::Level& l : t.levels) {
        levels.push_back({uint32_t(texels.size()), l.width, l.height, 0});
        const size_t n = size_t(l.width) * size_t(l.height);
        const size_t base = texels.size();
        texels.resize(base + n);
        std::memcpy(&texels[base], l.rgba.data(), n * 4);  // RGBA bytes: one little-endian uint
      }
      texs.push_back(g);
    }
    std::vector<GpuLight> lights;
    for (const Light& l : scene.lights) lights.push_back(gpuLight(l));
    std::vector<float> decode(512);
    for (int n = 0; n < 256; ++n) {
      decode[size_t(n)] = srgbToLinear(float(n) / 255.0f);
      decode[256 + size_t(n)] = float(n) / 255.0f;
    }
    stage(st, materials_, mats.data(), mats.size() * sizeof(GpuMaterial));
    stage(st, textures_, texs.data(), texs.size() * sizeof(GpuTexture));
    stage(st, levels_, levels.data(), levels.size() * sizeof(GpuTextureLevel));
    stage(st, texels_, texels.data(), texels.size() * 4);
    stage(st, lights_, lights.data(), lights.size() * sizeof(GpuLight));
    stage(st, decode_, decode.data(), decode.size() * 4);
    SceneArgs& a = sceneArgs_;
    a.lightCount = uint32_t(lights.size());
    for (int f = 0; f < 6; ++f)
      a.skyFaces[f] = scene.skybox.hasFaces() ? scene.skybox.faces[f] : -1;
    put(a.skyColor, scene.skybox.color);
    put(a.ambient, scene.ambient);
    a.environmentIor = scene.environmentIor;
  }
  // Vertices as the frame has them (world space), every object's after the one before.
  std::vector<GpuObject> objects;
  std::vector<Vec3> positions, normals, stepPositions, stepNormals;
  std::vector<Vec4> tangents;
  std::vector<Vec2> uvs;
  std::vector<uint32_t> indices;
  for (size_t o = 0; o < fs.objects.size(); ++o) {
    const FrameObject& fo = fs.objects[o];
    const Object& obj = scene.objects[o];
    const Mesh& mesh = scene.meshes[size_t(obj.mesh)];
    GpuObject g{};
    g.material = uint32_t(obj.material);
    g.firstVertex = uint32_t(positions.size());
    g.firstIndex = uint32_t(indices.size());
    g.hasUvs = mesh.uvs.empty() ? 0 : 1;
    g.hasTangents = fo.tangents.size() == fo.positions.size() ? 1 : 0;
    g.motionSteps = motionSteps(fo);
    g.firstStep = uint32_t(stepPositions.size());
    for (size_t v = 0; v < fo.positions.size() && g.motionSteps; ++v)
      for (size_t s = 0; s < g.motionSteps; ++s) {
        stepPositions.push_back(fo.stepPositions[s][v]);
        stepNormals.push_back(v < fo.stepNormals[s].size() ? fo.stepNormals[s][v] : Vec3(0.0f));
      }
    objects.push_back(g);
    positions.insert(positions.end(), fo.positions.begin(), fo.positions.end());
    normals.insert(normals.end(), fo.normals.begin(), fo.normals.end());
    if (g.hasTangents)
      tangents.insert(tangents.end(), fo.tangents.begin(), fo.tangents.end());
    else
      tangents.resize(positions.size());
    if (g.hasUvs)
      uvs.insert(uvs.end(), mesh.uvs.begin(), mesh.uvs.end());
    else
      uvs.resize(positions.size());
    indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
  }
  static_assert(sizeof(Vec3) == 12 && sizeof(Vec4) == 16 && sizeof(Vec2) == 8);
  stage(st, objectsBuf_, objects.data(), objects.size() * sizeof(GpuObject));
  stage(st, positions_, positions.data(), positions.size() * sizeof(Vec3));
  stage(st, normals_, normals.data(), normals.size() * sizeof(Vec3));
  stage(st, tangents_, tangents.data(), tangents.size() * sizeof(Vec4));
  stage(st, uvs_, uvs.data(), uvs.size() * sizeof(Vec2));
  stage(st, indices_, indices.data(), indices.size() * 4);
  stage(st, stepPositions_, stepPositions.data(), stepPositions.size() * sizeof(Vec3));
  stage(st, stepNormals_, stepNormals.data(), stepNormals.size() * sizeof(Vec3));
  SceneArgs& a = sceneArgs_;
  a.nodes = nodes_.address;
  a.triangles = triangles_.address;
  a.trianglePrim = prims_.address;
  a.objectRoot = roots_.address;
  a.topRoot = topRoot_;
  a.objects = objectsBuf_.address;
  a.materials = materials_.address;
  a.textures = textures_.address;
  a.levels = levels_.address;
  a.texels = texels_.address;
  a.lights = lights_.address;
  a.decode = decode_.address;
  a.positions = positions_.address;
  a.normals = normals_.address;
  a.tangents = tangents_.address;
  a.uvs = uvs_.address;
  a.indices = indices_.address;
  a.objectMotion = motion_.address;
  a.motionTriangles = motionTriangles_.address;
  a.stepPositions = stepPositions_.address;
  a.stepNormals = stepNormals_.address;
  stage(st, args_, &a, sizeof a);
}

TraceArgs GpuScene::traceArgs() const {
  TraceArgs a{};
  a.nodes = nodes_.address;
  a.triangles = triangles_.address;
  a.trianglePrim = prims_.address;
  a.objectRoot = roots_.address;
  a.topRoot = topRoot_;
  a.objectMotion = motion_.address;
  a.motionTriangles = motionTriangles_.address;
  return a;
}

uint64_t GpuScene::deviceBytes() const {
  uint64_t n = 0;
  for (const GpuBuffer* b :
       {&nodes_,         &triangles_,   &prims_,   &roots_,    &motion_, &motionTriangles_,
        &materials_,     &textures_,    &levels_,  &texels_,   &lights_, &decode_,
        &objectsBuf_,    &positions_,   &normals_, &tangents_, &uvs_,    &indices_,
        &stepPositions_, &stepNormals_, &args_})
    n += b->size;
  return n;
}

}  // namespace tandem
