#include "scene/primitives.h"

#include <cmath>
#include <utility>

namespace tandem {

namespace {

// Two triangles per cell of a vertex grid laid out row by row, `cols` + 1 vertices to a row.
void addGridTriangles(Mesh& m, int cols, int rows) {
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      uint32_t a = j * (cols + 1) + i, b = a + 1, c = a + cols + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
}

// Turns each triangle to face the way its first vertex's intended normal points.
void windAlongNormals(Mesh& m) {
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    uint32_t* i = &m.indices[3 * t];
    Vec3 fn = cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]);
    if (dot(fn, m.normals[i[0]]) < 0) std::swap(i[1], i[2]);
  }
}

}  // namespace

Mesh makePlane(int n) {
  n = std::max(1, n);
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      float u = float(i) / n, v = float(j) / n;
      m.positions.push_back({-1 + 2 * u, 0, -1 + 2 * v});
      m.normals.push_back({0, 1, 0});
      m.uvs.push_back({u, v});
    }
  addGridTriangles(m, n, n);
  completeMesh(m);
  return m;
}

Mesh makeCube() {
  Mesh m;
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3& n : axes) {
    Vec3 t, b;
    // Pick in-face axes so that t x b = n (counter-clockwise faces seen from outside).
    if (std::abs(n.y) > 0.5f) {
      t = {1, 0, 0};
    } else {
      t = {0, 1, 0};
    }
    b = cross(n, t);
    uint32_t base = uint32_t(m.positions.size());
    const float cs[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (auto& c : cs) {
      m.positions.push_back(n + t * c[0] + b * c[1]);
      m.normals.push_back(n);
      m.uvs.push_back({0.5f * (c[0] + 1), 0.5f * (c[1] + 1)});
    }
    // Orientation check: (p1-p0) x (p2-p0) must point along n.
    Vec3 fn =
        cross(m.positions[base + 1] - m.positions[base], m.positions[base + 2] - m.positions[base]);
    if (dot(fn, n) > 0)
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    else
      m.indices.insert(m.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
  }
  completeMesh(m);
  return m;
}

Mesh makeUvSphere(int slices, int stacks) {
  slices = std::max(3, slices);
  stacks = std::max(2, stacks);
  Mesh m;
  for (int j = 0; j <= stacks; ++j) {
    float v = float(j) / stacks, theta = v * kPi;
    for (int i = 0; i <= slices; ++i) {
      float u = float(i) / slices, phi = u * 2 * kPi;
      Vec3 p{std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
      m.positions.push_back(p);
      m.normals.push_back(p);
      m.uvs.push_back({u, v});
    }
  }
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      uint32_t a = j * (slices + 1) + i, b = a + 1, c = a + slices + 1, d = c + 1;
      if (j != 0) m.indices.insert(m.indices.end(), {a, c, b});
      if (j != stacks - 1) m.indices.insert(m.indices.end(), {b, c, d});
    }
  completeMesh(m);
  return m;
}

Mesh makeCylinder(int segments, int rings, bool caps) {
  Mesh m;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i <= segments; ++i) {
      float u = float(i) / segments, v = float(j) / rings, phi = u * 2 * kPi;
      Vec3 n{std::cos(phi), 0, -std::sin(phi)};
      m.positions.push_back({n.x, v, n.z});
      m.normals.push_back(n);
      m.uvs.push_back({u * 4, v});
    }
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      uint32_t a = j * (segments + 1) + i, b = a + 1, c = a + segments + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
    }
  if (caps) {
    for (int cap = 0; cap < 2; ++cap) {
      float y = float(cap);
      Vec3 n{0, cap ? 1.0f : -1.0f, 0};
      uint32_t centre = uint32_t(m.positions.size());
      m.positions.push_back({0, y, 0});
      m.normals.push_back(n);
      m.uvs.push_back({0.5f, 0.5f});
      for (int i = 0; i <= segments; ++i) {
        float phi = float(i) / segments * 2 * kPi;
        m.positions.push_back({std::cos(phi), y, -std::sin(phi)});
        m.normals.push_back(n);
        m.uvs.push_back({0.5f + 0.5f * std::cos(phi), 0.5f + 0.5f * std::sin(phi)});
      }
      for (int i = 0; i < segments; ++i) {
        uint32_t a = centre + 1 + i, b = a + 1;
        if (cap)
          m.indices.insert(m.indices.end(), {centre, a, b});
        else
          m.indices.insert(m.indices.end(), {centre, b, a});
      }
    }
  }
  completeMesh(m);
  return m;
}

Mesh makeArch(float r0, float r1, float depth, int segments) {
  // Built as a swept quad cross-section: inner face, outer face, front and back faces.
  Mesh m;
  auto quadStrip = [&](auto point, auto normal) {
    uint32_t base = uint32_t(m.positions.size());
    for (int i = 0; i <= segments; ++i) {
      float a = kPi * float(i) / segments;
      for (int k = 0; k < 2; ++k) {
        m.positions.push_back(point(a, k));
        m.normals.push_back(normal(a));
        m.uvs.push_back({float(i) / segments * 3, float(k)});
      }
    }
    for (int i = 0; i < segments; ++i) {
      uint32_t a = base + 2 * i;
      m.indices.insert(m.indices.end(), {a, a + 2, a + 1, a + 1, a + 2, a + 3});
    }
  };
  float hz = depth * 0.5f;
  auto dir = [](float a) { return Vec3(std::cos(a), std::sin(a), 0); };
  quadStrip([&](float a, int k) { return dir(a) * r0 + Vec3(0, 0, k ? -hz : hz); },
            [&](float a) { return -dir(a); });
  quadStrip([&](float a, int k) { return dir(a) * r1 + Vec3(0, 0, k ? hz : -hz); },
            [&](float a) { return dir(a); });
  quadStrip([&](float a, int k) { return dir(a) * (k ? r0 : r1) + Vec3(0, 0, hz); },
            [&](float) { return Vec3(0, 0, 1); });
  quadStrip([&](float a, int k) { return dir(a) * (k ? r1 : r0) + Vec3(0, 0, -hz); },
            [&](float) { return Vec3(0, 0, -1); });
  windAlongNormals(m);  // each strip's winding follows its intended normal
  completeMesh(m);
  return m;
}

Mesh makeTorusKnot(int p, int q, float tube, int segments, int sides) {
  segments = std::max(8, segments);
  sides = std::max(3, sides);
  // The curve on a torus of radii 2 and 1, with analytic first and second derivatives for the
  // Frenet frame (a torus knot's curvature never vanishes, so the frame is smooth and closed).
  auto curve = [&](float t, Vec3& d1, Vec3& d2) {
    float cq = std::cos(q * t), sq = std::sin(q * t), cp = std::cos(p * t), sp = std::sin(p * t);
    float r = 2 + cq, dr = -q * sq, ddr = -q * q * cq;
    d1 = {dr * cp - r * p * sp, dr * sp + r * p * cp, -q * cq};
    d2 = {ddr * cp - 2 * dr * p * sp - r * p * p * cp, ddr * sp + 2 * dr * p * cp - r * p * p * sp,
          q * q * sq};
    return Vec3(r * cp, r * sp, -sq);
  };
  float scale = 1.0f / (3 + tube);
  Mesh m;
  for (int i = 0; i <= segments; ++i) {
    float u = float(i) / segments;
    Vec3 d1, d2;
    Vec3 c = curve(u * 2 * kPi, d1, d2);
    Vec3 t = normalize(d1);
    Vec3 n = normalize(d2 - t * dot(d2, t));
    Vec3 b = cross(t, n);
    for (int j = 0; j <= sides; ++j) {
      float v = float(j) / sides, a = v * 2 * kPi;
      Vec3 dir = n * std::cos(a) + b * std::sin(a);
      m.positions.push_back((c + dir * tube) * scale);
      m.normals.push_back(dir);
      m.uvs.push_back({u * 8, v});
    }
  }
  addGridTriangles(m, sides, segments);
  windAlongNormals(m);  // outwards, whichever way the Frenet frame turns
  completeMesh(m);
  return m;
}

Mesh makeCloth(float w, float h, int nx, int ny, float foldDepth, int folds) {
  Mesh m;
  auto pos = [&](float u, float v) {
    // Folds deepen towards the bottom, as a banner pinned along its top edge.
    return Vec3((u - 0.5f) * w, -v * h, foldDepth * v * std::sin(u * folds * 2 * kPi));
  };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      float u = float(i) / nx, v = float(j) / ny;
      m.positions.push_back(pos(u, v));
      m.uvs.push_back({u, v});
    }
  addGridTriangles(m, nx, ny);
  // Analytic-free normals: averaged face normals over the shared grid (smooth everywhere).
  m.normals.assign(m.positions.size(), Vec3(0.0f));
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* i = &m.indices[3 * t];
    Vec3 fn = cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]);
    for (int k = 0; k < 3; ++k) m.normals[i[k]] += fn;
  }
  completeMesh(m);
  return m;
}

}  // namespace tandem
