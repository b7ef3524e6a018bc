#include "scene/polygon_triangulation.h"

#include <cmath>

namespace tandem {

namespace {

// Twice the signed area of triangle (a, b, c) in the plane.
inline double cross2(const double* a, const double* b, const double* c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

std::vector<std::array<uint32_t, 3>> fan(size_t n) {
  std::vector<std::array<uint32_t, 3>> t;
  t.reserve(n - 2);
  for (size_t i = 1; i + 1 < n; ++i) t.push_back({0u, uint32_t(i), uint32_t(i + 1)});
  return t;
}

}  // namespace

std::vector<std::array<uint32_t, 3>> triangulatePolygon(const std::vector<Vec3>& p) {
  const size_t n = p.size();
  if (n < 3) return {};
  if (n == 3) return {{0u, 1u, 2u}};
  // The polygon's plane (Newell's normal), then 2D coordinates dropping its largest axis.
  double nx = 0, ny = 0, nz = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 &a = p[i], &b = p[(i + 1) % n];
    nx += double(a.y - b.y) * double(a.z + b.z);
    ny += double(a.z - b.z) * double(a.x + b.x);
    nz += double(a.x - b.x) * double(a.y + b.y);
  }
  const double ax = std::abs(nx), ay = std::abs(ny), az = std::abs(nz);
  const int drop = ax >= ay && ax >= az ? 0 : ay >= az ? 1 : 2;
  std::vector<double> q(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const double c[3] = {p[i].x, p[i].y, p[i].z};
    q[2 * i] = c[drop == 0 ? 1 : 0];
    q[2 * i + 1] = c[drop == 2 ? 1 : 2];
  }
  // Orientation of the projected polygon (its signed area's sign).
  double area = 0;
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    area += q[2 * i] * q[2 * j + 1] - q[2 * j] * q[2 * i + 1];
  }
  const double sign = area >= 0 ? 1.0 : -1.0;
  bool convex = true;
  for (size_t i = 0; i < n && convex; ++i)
    convex = sign * cross2(&q[2 * i], &q[2 * ((i + 1) % n)], &q[2 * ((i + 2) % n)]) >= 0;
  if (convex || n > kMaxEarClipVertices || area == 0) return fan(n);

  // Ear clipping: a convex corner whose triangle holds no other remaining vertex is cut off.
  std::vector<uint32_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = uint32_t(i);
  std::vector<std::array<uint32_t, 3>> out;
  out.reserve(n - 2);
  size_t misses = 0;
  for (size_t i = 0; v.size() > 3;) {
    const size_t m = v.size();
    const uint32_t a = v[(i + m - 1) % m], b = v[i % m], c = v[(i + 1) % m];
    const double *pa = &q[2 * a], *pb = &q[2 * b], *pc = &q[2 * c];
    bool ear = sign * cross2(pa, pb, pc) > 0;
    for (size_t k = 0; k < m && ear; ++k) {
      const uint32_t w = v[k];
      if (w == a || w == b || w == c) continue;
      const double* pw = &q[2 * w];
      ear = !(sign * cross2(pa, pb, pw) >= 0 && sign * cross2(pb, pc, pw) >= 0 &&
              sign * cross2(pc, pa, pw) >= 0);
    }
    if (ear || misses > m) {  // no ear left (self-intersecting input): cut it anyway
      out.push_back({a, b, c});
      v.erase(v.begin() + std::ptrdiff_t(i % m));
      misses = 0;
      if (i >= v.size()) i = 0;
    } else {
      ++misses;
      i = (i + 1) % m;
    }
  }
  out.push_back({v[0], v[1], v[2]});
  return out;
}

}  // namespace tandem
