#include "scene/mesh.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace tandem {

size_t Mesh::memoryBytes() const {
  return positions.size() * sizeof(Vec3) + normals.size() * sizeof(Vec3) +
         tangents.size() * sizeof(Vec4) + uvs.size() * sizeof(Vec2) +
         indices.size() * sizeof(uint32_t);
}

size_t removeDegenerateTriangles(Mesh& m) {
  size_t kept = 0, removed = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
    bool degenerate = a == b || b == c || a == c;
    if (!degenerate) {
      Vec3 n = cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
      degenerate = !(dot(n, n) > 0.0f);
    }
    if (degenerate) {
      ++removed;
      continue;
    }
    m.indices[3 * kept] = a;
    m.indices[3 * kept + 1] = b;
    m.indices[3 * kept + 2] = c;
    ++kept;
  }
  m.indices.resize(3 * kept);
  return removed;
}

void computeNormals(Mesh& m, float creaseDeg) {
  const size_t nt = m.triangleCount();
  std::vector<Vec3> faceN(nt);
  std::vector<std::vector<uint32_t>> vertexFaces(m.positions.size());
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* i = &m.indices[3 * t];
    faceN[t] = cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]);
    for (int k = 0; k < 3; ++k) vertexFaces[i[k]].push_back(uint32_t(t));
  }
  // Vertices that are shared by coincident positions only through separate indices stay split;
  // smoothing happens across faces that share an index.
  const float cosCrease = std::cos(radians(creaseDeg));
  Mesh out;
  out.positions.reserve(m.positions.size());
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> remap;  // (vertex, smoothing group rep) -> new
  std::vector<uint32_t> newIndices(m.indices.size());
  // A corner's group depends only on its face's normal: corners of faces with the same normal
  // at a vertex reuse it (a fan of 100k coplanar triangles costs 100k, not 100k^2). Around a
  // vertex of more than kMaxCreaseValence faces, all of them form one group.
  constexpr size_t kMaxCreaseValence = 1024;
  struct Group {
    Vec3 nf, sum;
    uint32_t rep;
  };
  std::vector<std::vector<Group>> groups(m.positions.size());
  for (size_t t = 0; t < nt; ++t) {
    Vec3 nf = normalize(faceN[t]);
    for (int k = 0; k < 3; ++k) {
      uint32_t v = m.indices[3 * t + k];
      const bool crowded = vertexFaces[v].size() > kMaxCreaseValence;
      const Group* known = nullptr;
      for (const Group& g : groups[v])
        if (crowded || (g.nf.x == nf.x && g.nf.y == nf.y && g.nf.z == nf.z)) {
          known = &g;
          break;
        }
      Vec3 sum(0.0f);
      uint32_t rep = UINT32_MAX;  // smallest face id in this corner's group: a stable key
      if (known) {
        sum = known->sum;
        rep = known->rep;
      } else {
        for (uint32_t f : vertexFaces[v]) {
          if (crowded || dot(normalize(faceN[f]), nf) >= cosCrease) {
            sum += faceN[f];
            rep = std::min(rep, f);
          }
        }
        if (groups[v].size() < 64) groups[v].push_back({nf, sum, rep});
      }
      auto key = std::make_pair(v, rep);
      auto it = remap.find(key);
      if (it == remap.end()) {
        uint32_t id = uint32_t(out.positions.size());
        out.positions.push_back(m.positions[v]);
        out.normals.push_back(length(sum) > 0 ? normalize(sum) : Vec3(0, 1, 0));
        if (!m.uvs.empty()) out.uvs.push_back(m.uvs[v]);
        it = remap.emplace(key, id).first;
      }
      newIndices[3 * t + k] = it->second;
    }
  }
  m.positions = std::move(out.positions);
  m.normals = std::move(out.normals);
  if (!m.uvs.empty()) m.uvs = std::move(out.uvs);
  m.tangents.clear();
  m.indices = std::move(newIndices);
}

void computeTangents(Mesh& m) {
  const size_t nv = m.positions.size();
  std::vector<Vec3> tan(nv, Vec3(0.0f)), bit(nv, Vec3(0.0f));
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* i = &m.indices[3 * t];
    Vec3 e1 = m.positions[i[1]] - m.positions[i[0]], e2 = m.positions[i[2]] - m.positions[i[0]];
    Vec2 d1 = m.uvs[i[1]] - m.uvs[i[0]], d2 = m.uvs[i[2]] - m.uvs[i[0]];
    float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-20f) continue;
    float r = 1.0f / det;
    Vec3 sdir = (e1 * d2.y - e2 * d1.y) * r;
    Vec3 tdir = (e2 * d1.x - e1 * d2.x) * r;
    for (int k = 0; k < 3; ++k) {
      tan[i[k]] += sdir;
      bit[i[k]] += tdir;
    }
  }
  m.tangents.resize(nv);
  for (size_t v = 0; v < nv; ++v) {
    Vec3 n = m.normals[v];
    Vec3 t = tan[v] - n * dot(n, tan[v]);
    if (!(dot(t, t) > 1e-20f) || !isFinite(t)) {
      Vec3 b;
      orthonormalBasis(n, t, b);
    }
    t = normalize(t);
    float w = dot(cross(n, t), bit[v]) < 0.0f ? -1.0f : 1.0f;
    m.tangents[v] = Vec4(t, w);
  }
}

void computeMikkTSpaceTangents(Mesh& m) {
  // MikkTSpace's construction (Mikkelsen 2008, the glTF default when a normal-mapped mesh has
  // no tangents), so normal maps baked against it shade as their bakers intended: at each
  // corner the face's dP/du is projected onto the vertex normal's plane and weighted by the
  // corner angle measured in that plane; corners are summed per vertex and per UV orientation
  // (mirrored faces form their own group, and a vertex used by both orientations is split);
  // w is the group's orientation, so the bitangent w * cross(n, t) follows dP/dv.
  const size_t nv = m.positions.size();
  enum : uint8_t { kNone = 0, kPreserving = 1, kMirrored = 2 };
  std::vector<uint8_t> used(nv, kNone);
  std::vector<int8_t> faceOrientation(m.triangleCount(), 0);  // +1, -1, 0 (no UV area)
  std::vector<Vec3> faceTangent(m.triangleCount(), Vec3(0.0f));
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* i = &m.indices[3 * t];
    const Vec3 e1 = m.positions[i[1]] - m.positions[i[0]];
    const Vec3 e2 = m.positions[i[2]] - m.positions[i[0]];
    const Vec2 d1 = m.uvs[i[1]] - m.uvs[i[0]], d2 = m.uvs[i[2]] - m.uvs[i[0]];
    const float det = d1.x * d2.y - d2.x * d1.y;
    const Vec3 dPdu = (e1 * d2.y - e2 * d1.y) * (1.0f / det);
    if (!(std::abs(det) > 1e-20f) || !isFinite(dPdu)) continue;
    faceOrientation[t] = det > 0 ? 1 : -1;
    faceTangent[t] = dPdu;
    for (int k = 0; k < 3; ++k) used[i[k]] |= det > 0 ? kPreserving : kMirrored;
  }
  // Split vertices whose corners disagree on orientation: mirrored faces get a copy.
  std::vector<uint32_t> mirroredCopy(nv, UINT32_MAX);
  for (size_t v = 0; v < nv; ++v)
    if (used[v] == (kPreserving | kMirrored)) {
      mirroredCopy[v] = uint32_t(m.positions.size());
      m.positions.push_back(m.positions[v]);
      m.normals.push_back(m.normals[v]);
      m.uvs.push_back(m.uvs[v]);
    }
  for (size_t t = 0; t < m.triangleCount(); ++t)
    if (faceOrientation[t] < 0)
      for (int k = 0; k < 3; ++k)
        if (mirroredCopy[m.indices[3 * t + k]] != UINT32_MAX)
          m.indices[3 * t + k] = mirroredCopy[m.indices[3 * t + k]];
  const size_t n = m.positions.size();
  std::vector<Vec3> sum(n, Vec3(0.0f));
  std::vector<float> sign(n, 1.0f);
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    if (faceOrientation[t] == 0) continue;
    const uint32_t* i = &m.indices[3 * t];
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = i[k];
      const Vec3 nrm = m.normals[v];
      auto inPlane = [&](Vec3 x) { return x - nrm * dot(nrm, x); };
      const Vec3 t0 = inPlane(faceTangent[t]);
      const Vec3 ea = inPlane(m.positions[i[(k + 1) % 3]] - m.positions[v]);
      const Vec3 eb = inPlane(m.positions[i[(k + 2) % 3]] - m.positions[v]);
      const float la = length(ea), lb = length(eb), lt = length(t0);
      if (!(la > 0 && lb > 0 && lt > 0)) continue;
      const float angle = std::acos(std::clamp(dot(ea, eb) / (la * lb), -1.0f, 1.0f));
      sum[v] += t0 * (angle / lt);
      sign[v] = float(faceOrientation[t]);
    }
  }
  m.tangents.resize(n);
  for (size_t v = 0; v < n; ++v) {
    const Vec3 nrm = m.normals[v];
    Vec3 t = sum[v] - nrm * dot(nrm, sum[v]);
    if (!(dot(t, t) > 1e-20f) || !isFinite(t)) {
      Vec3 b;
      orthonormalBasis(nrm, t, b);
    }
    m.tangents[v] = Vec4(normalize(t), sign[v]);
  }
}

void completeMesh(Mesh& m) {
  if (m.normals.size() != m.positions.size()) computeNormals(m);
  for (Vec3& n : m.normals) n = length(n) > 0 ? normalize(n) : Vec3(0, 1, 0);
  if (m.uvs.size() != m.positions.size()) m.uvs.assign(m.positions.size(), Vec2(0, 0));
  if (m.tangents.size() != m.positions.size()) computeTangents(m);
}

}  // namespace tandem
