#include "scene/frame_scene.h"

#include <cstring>

#include "core/parallel.h"

namespace tandem {

namespace {
bool sameMatrix(const Mat4& a, const Mat4& b) {
  return std::memcmp(&a, &b, sizeof(Mat4)) == 0;
}
}  // namespace

void FrameScene::update(const Scene& s, float t, float tPrev) {
  bool first = scene != &s || objects.size() != s.objects.size();
  scene = &s;
  time = t;
  prevTime = tPrev;
  if (first) objects.assign(s.objects.size(), FrameObject{});
  bool changed = first;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    FrameObject& f = objects[i];
    Mat4 w = o.worldMatrix(t);
    f.prevWorld = o.worldMatrix(tPrev);
    f.worldToPrev = f.prevWorld * w.inverse();
    f.moved = !sameMatrix(f.prevWorld, w);
    if (!first && sameMatrix(w, f.world)) continue;
    changed = true;
    f.world = w;
    f.normalMatrix = w.normalMatrix();
    const Mesh& m = s.meshes[o.mesh];
    f.positions.resize(m.positions.size());
    f.normals.resize(m.normals.size());
    f.tangents.resize(m.tangents.size());
    parallelRange(m.positions.size(), [&](size_t b, size_t e) {
      for (size_t v = b; v < e; ++v) {
        f.positions[v] = w.transformPoint(m.positions[v]);
        f.normals[v] = normalize(f.normalMatrix.transformVector(m.normals[v]));
        Vec4 tg = m.tangents[v];
        f.tangents[v] = Vec4(normalize(w.transformVector(tg.xyz())), tg.w);
      }
    });
  }
  if (changed) ++geometryVersion;
}

}  // namespace tandem
