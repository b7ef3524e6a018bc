#include "scene/polygon_triangulation.h"

#include <algorithm>
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

// Ear clipping over a linked ring of the remaining vertices. Only reflex vertices can lie
// inside a candidate ear, so they alone are kept, in a uniform grid over the polygon's box: an
// ear test looks at the few cells its triangle's box covers. Typical polygons take O(n) tests;
// the total work is capped (kWorkPerVertex tests a vertex) and whatever remains past the cap is
// a fan, so no input, however contrived, takes long.
class EarClipper {
 public:
  EarClipper(const std::vector<double>& q, double sign) : q_(q), sign_(sign), n_(q.size() / 2) {
    next_.resize(n_);
    prev_.resize(n_);
    reflex_.assign(n_, 0);
    for (size_t i = 0; i < n_; ++i) {
      next_[i] = uint32_t((i + 1) % n_);
      prev_[i] = uint32_t((i + n_ - 1) % n_);
    }
    lo_[0] = lo_[1] = 1e300;
    double hi[2] = {-1e300, -1e300};
    for (size_t i = 0; i < n_; ++i)
      for (int k = 0; k < 2; ++k)
        lo_[k] = std::min(lo_[k], q[2 * i + k]), hi[k] = std::max(hi[k], q[2 * i + k]);
    for (size_t i = 0; i < n_; ++i) reflexLeft_ += reflex_[i] = !convex(uint32_t(i));
    g_ = std::max<size_t>(1, size_t(2.0 * std::sqrt(double(reflexLeft_))));
    for (int k = 0; k < 2; ++k) scale_[k] = double(g_) / std::max(hi[k] - lo_[k], 1e-300);
    cells_.assign(g_ * g_, {});
    for (size_t i = 0; i < n_; ++i)
      if (reflex_[i]) cells_[cellOf(uint32_t(i))].push_back(uint32_t(i));
  }

  std::vector<std::array<uint32_t, 3>> run() {
    std::vector<std::array<uint32_t, 3>> out;
    out.reserve(n_ - 2);
    size_t left = n_, misses = 0, work = 0;
    const size_t budget = kWorkPerVertex * n_ + 4096;
    uint32_t b = 0;
    while (left > 3) {
      const uint32_t a = prev_[b], c = next_[b];
      // A vertex on the line through its neighbours cuts off no area: always safe to clip.
      const double turn = sign_ * cross2(p(a), p(b), p(c));
      // Once no reflex vertex remains the rest is convex: every convex corner is an ear, and
      // clipping on (rather than fanning) keeps the triangles well shaped.
      const bool ear = turn == 0 || (turn > 0 && (reflexLeft_ == 0 || empty(a, b, c, &work)));
      if (ear || misses > left || work > budget) {
        if (work > budget) {
          // Out of budget (a contrived input): the rest as a fan around b.
          for (uint32_t v = c; next_[v] != b; v = next_[v]) out.push_back({b, v, next_[v]});
          return out;
        }
        out.push_back({a, b, c});  // an ear, or no ear left (self-intersecting): cut anyway
        next_[a] = c, prev_[c] = a;
        --left;
        if (reflex_[b]) reflex_[b] = 0, --reflexLeft_;  // a collinear or force-cut vertex
        misses = 0;
        for (uint32_t v : {a, c})
          if (reflex_[v] && convex(v)) reflex_[v] = 0, --reflexLeft_;  // convex from now on
        // On past c, as mapbox's earcut does: stepping back to a would pivot a long fan of
        // ever longer triangles around c (quadratic on a star); skipping ahead clips a
        // star's tips in one round.
        b = next_[c];
      } else {
        ++misses;
        b = c;
      }
    }
    for (uint32_t v = next_[b]; next_[v] != b; v = next_[v]) out.push_back({b, v, next_[v]});
    return out;
  }

 private:
  static constexpr size_t kWorkPerVertex = 1024;
  const std::vector<double>& q_;
  const double sign_;
  const size_t n_;
  std::vector<uint32_t> next_, prev_;
  std::vector<char> reflex_;
  size_t reflexLeft_ = 0;
  size_t g_ = 1;
  double lo_[2], scale_[2];
  std::vector<std::vector<uint32_t>> cells_;

  const double* p(uint32_t i) const { return &q_[2 * size_t(i)]; }
  bool convex(uint32_t b) const { return sign_ * cross2(p(prev_[b]), p(b), p(next_[b])) > 0; }
  size_t cellCoord(double v, int k) const {
    const double c = (v - lo_[k]) * scale_[k];
    return c <= 0 ? 0 : std::min(g_ - 1, size_t(c));
  }
  size_t cellOf(uint32_t i) const { return cellCoord(p(i)[1], 1) * g_ + cellCoord(p(i)[0], 0); }

  // No remaining reflex vertex inside (or on) triangle (a, b, c).
  bool empty(uint32_t a, uint32_t b, uint32_t c, size_t* work) const {
    const double *pa = p(a), *pb = p(b), *pc = p(c);
    const size_t x0 = cellCoord(std::min({pa[0], pb[0], pc[0]}), 0);
    const size_t x1 = cellCoord(std::max({pa[0], pb[0], pc[0]}), 0);
    const size_t y0 = cellCoord(std::min({pa[1], pb[1], pc[1]}), 1);
    const size_t y1 = cellCoord(std::max({pa[1], pb[1], pc[1]}), 1);
    for (size_t y = y0; y <= y1; ++y)
      for (size_t x = x0; x <= x1; ++x)
        for (uint32_t w : cells_[y * g_ + x]) {
          ++*work;
          if (!reflex_[w] || w == a || w == b || w == c) continue;
          if (next_[prev_[w]] != w) continue;  // already clipped
          const double* pw = p(w);
          if (sign_ * cross2(pa, pb, pw) >= 0 && sign_ * cross2(pb, pc, pw) >= 0 &&
              sign_ * cross2(pc, pa, pw) >= 0)
            return false;
        }
    ++*work;
    return true;
  }
};

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
  if (convex || area == 0 || !std::isfinite(area)) return fan(n);
  return EarClipper(q, sign).run();
}

}  // namespace tandem
