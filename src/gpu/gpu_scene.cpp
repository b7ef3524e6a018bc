#include "gpu/gpu_scene.h"

#include <cstring>

#include "gpu/gpu_bvh.h"

namespace tandem {

namespace {
bool samePositions(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}
}  // namespace

GpuScene::~GpuScene() {
  for (GpuBuffer* b : {&nodes_, &triangles_, &prims_, &roots_, &staging_}) memory_.release(*b);
}

GpuScene::ObjectBvh GpuScene::buildObject(const Scene& scene, const FrameObject& o, size_t index) {
  const Mesh& mesh = scene.meshes[size_t(scene.objects[index].mesh)];
  const size_t n = mesh.triangleCount();
  std::vector<Bounds3> boxes(n);
  for (size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) boxes[t].extend(o.positions[mesh.indices[3 * t + size_t(k)]]);
  BvhBuild b = buildBvh(boxes);
  ObjectBvh out;
  out.nodes = std::move(b.nodes);
  out.triangles.reserve(n * 9);
  out.prims = std::move(b.items);
  for (const uint32_t t : out.prims)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = o.positions[mesh.indices[3 * size_t(t) + size_t(k)]];
      out.triangles.insert(out.triangles.end(), {p.x, p.y, p.z});
    }
  for (const Bounds3& box : boxes) out.bounds.extend(box);
  return out;
}

void GpuScene::refitObject(ObjectBvh& ob, const Scene& scene, const FrameObject& o, size_t index) {
  const Mesh& mesh = scene.meshes[size_t(scene.objects[index].mesh)];
  for (size_t i = 0; i < ob.prims.size(); ++i)
    for (size_t k = 0; k < 3; ++k) {
      const Vec3 p = o.positions[mesh.indices[3 * size_t(ob.prims[i]) + k]];
      float* v = &ob.triangles[9 * i + 3 * k];
      v[0] = p.x, v[1] = p.y, v[2] = p.z;
    }
  // Children always follow their parent (buildBvh's order): from the last node back, every
  // child's box is final before its parent's is drawn around it.
  for (size_t n = ob.nodes.size(); n-- > 0;) {
    BvhNode& node = ob.nodes[n];
    if (node.lox > node.hix) continue;  // an empty slot stays empty
    Bounds3 b;
    if (node.count) {
      for (size_t t = node.a; t < node.a + node.count; ++t)
        for (size_t k = 0; k < 3; ++k)
          b.extend({ob.triangles[9 * t + 3 * k], ob.triangles[9 * t + 3 * k + 1],
                    ob.triangles[9 * t + 3 * k + 2]});
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
  if (fs.geometryVersion == version_ && fs.scene == scene_ && fs.objects.size() == objects_.size())
    return;
  const Scene& scene = *fs.scene;
  const bool fresh = fs.scene != scene_ || objects_.size() != fs.objects.size();
  objects_.resize(fs.objects.size());
  built_.resize(fs.objects.size());
  for (size_t o = 0; o < fs.objects.size(); ++o) {
    const FrameObject& fo = fs.objects[o];
    if (!fresh && samePositions(built_[o], fo.positions)) continue;  // only what moved
    // A BVH built for these triangles is refitted (its tree kept, its boxes redrawn around where
    // the triangles are now): cheaper than a build, and rigid motion barely loosens the boxes.
    if (!fresh && built_[o].size() == fo.positions.size())
      refitObject(objects_[o], scene, fo, o);
    else
      objects_[o] = buildObject(scene, fo, o);
    built_[o] = fo.positions;
  }
  scene_ = fs.scene;
  version_ = fs.geometryVersion;
  upload(cmd);
}

GpuBuffer& GpuScene::ensure(GpuBuffer& b, size_t bytes) {
  if (b && b.size < bytes) memory_.release(b);
  if (!b) b = memory_.allocate(bytes, false);
  return b;
}

void GpuScene::upload(GpuCommands& cmd) {
  // One array of nodes (each object's, offset, then the top level's), one of triangles.
  std::vector<BvhNode> nodes;
  std::vector<float> tris;
  std::vector<uint32_t> prims, roots(objects_.size());
  std::vector<Bounds3> boxes(objects_.size());
  for (size_t o = 0; o < objects_.size(); ++o) {
    const ObjectBvh& ob = objects_[o];
    const uint32_t nodeBase = uint32_t(nodes.size()), triBase = uint32_t(prims.size());
    roots[o] = nodeBase;
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

  const size_t nodeBytes = nodes.size() * sizeof(BvhNode), triBytes = tris.size() * 4,
               primBytes = prims.size() * 4, rootBytes = roots.size() * 4;
  const size_t total = nodeBytes + triBytes + primBytes + rootBytes;
  ensure(nodes_, nodeBytes);
  ensure(triangles_, triBytes);
  ensure(prims_, primBytes);
  ensure(roots_, rootBytes);
  if (staging_ && staging_.size < total) memory_.release(staging_);
  if (!staging_) staging_ = memory_.allocate(total, true);
  char* s = static_cast<char*>(staging_.mapped);
  std::memcpy(s, nodes.data(), nodeBytes);
  std::memcpy(s + nodeBytes, tris.data(), triBytes);
  std::memcpy(s + nodeBytes + triBytes, prims.data(), primBytes);
  std::memcpy(s + nodeBytes + triBytes + primBytes, roots.data(), rootBytes);
  cmd.begin();
  cmd.copy(staging_, nodes_, nodeBytes, 0);
  cmd.copy(staging_, triangles_, triBytes, nodeBytes);
  cmd.copy(staging_, prims_, primBytes, nodeBytes + triBytes);
  cmd.copy(staging_, roots_, rootBytes, nodeBytes + triBytes + primBytes);
  cmd.submit();
}

TraceArgs GpuScene::traceArgs() const {
  TraceArgs a{};
  a.nodes = nodes_.address;
  a.triangles = triangles_.address;
  a.trianglePrim = prims_.address;
  a.objectRoot = roots_.address;
  a.topRoot = topRoot_;
  return a;
}

uint64_t GpuScene::deviceBytes() const {
  return nodes_.size + triangles_.size + prims_.size + roots_.size;
}

}  // namespace tandem
