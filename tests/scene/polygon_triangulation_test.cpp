// Polygons of any size triangulate in bounded time into n - 2 triangles that tile the polygon:
// no gaps, no overlaps (their areas add up to the polygon's, all wound like it), and OBJ faces of
// 100k vertices load.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "scene/loaders.h"
#include "scene/polygon_triangulation.h"
#include "test_util.h"

using namespace tandem;

namespace {

// Signed area in the z = 0 plane.
double signedArea(const std::vector<Vec3>& p) {
  double a = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3 &u = p[i], &v = p[(i + 1) % p.size()];
    a += double(u.x) * v.y - double(v.x) * u.y;
  }
  return 0.5 * a;
}

// The triangles tile the polygon: n - 2 of them, each wound like it, areas adding up.
void expectTiling(const std::vector<Vec3>& p) {
  const auto tris = triangulatePolygon(p);
  ASSERT_EQ(tris.size(), p.size() - 2);
  const double total = signedArea(p);
  double sum = 0;
  for (const auto& t : tris) {
    const double a = signedArea({p[t[0]], p[t[1]], p[t[2]]});
    EXPECT_GE(a * total, 0.0) << "a triangle wound against the polygon";
    sum += a;
  }
  EXPECT_NEAR(sum, total, 1e-6 * std::abs(total));
}

std::vector<Vec3> star(int points, float inner, bool clockwise) {
  std::vector<Vec3> p;
  for (int i = 0; i < 2 * points; ++i) {
    const float a = 3.14159265f * float(i) / float(points) * (clockwise ? -1.0f : 1.0f);
    const float r = i % 2 ? inner : 1.0f;
    p.push_back({r * std::cos(a), r * std::sin(a), 0});
  }
  return p;
}

}  // namespace

TEST(PolygonTriangulation, ConvexAndConcavePolygonsAreTiled) {
  expectTiling({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});  // a quad
  std::vector<Vec3> circle;
  for (int i = 0; i < 40; ++i)
    circle.push_back({std::cos(0.157f * float(i)), std::sin(0.157f * float(i)), 0});
  expectTiling(circle);
  expectTiling(star(5, 0.4f, false));  // concave: ear clipping
  expectTiling(star(12, 0.2f, true));  // the other winding
  // An L shape (one reflex corner).
  expectTiling({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}});
  EXPECT_TRUE(triangulatePolygon({{0, 0, 0}, {1, 0, 0}}).empty());
}

// A polygon in another plane: the projection drops the right axis.
TEST(PolygonTriangulation, PolygonsInAnyPlane) {
  std::vector<Vec3> s = star(6, 0.5f, false), rotated;
  for (const Vec3& v : s) rotated.push_back({0.3f, v.x, v.y});  // in x = 0.3
  const auto tris = triangulatePolygon(rotated);
  ASSERT_EQ(tris.size(), s.size() - 2);
  double sum = 0;
  for (const auto& t : tris) sum += signedArea({s[t[0]], s[t[1]], s[t[2]]});
  EXPECT_NEAR(sum, signedArea(s), 1e-6);
}

// A face of 100k vertices (tinyobjloader's triangulation took minutes) and a non-convex one past
// the ear-clipping bound load, every vertex kept.
TEST(ObjLoader, HugePolygonsLoad) {
  const auto dir = test::scratchDir("huge_polygon");
  for (const bool convex : {true, false}) {
    const int n = convex ? 100000 : 30000;
    const std::string path = (dir / (convex ? "circle.obj" : "zigzag.obj")).string();
    std::ofstream f(path);
    for (int i = 0; i < n; ++i) {
      const float a = 6.2831853f * float(i) / float(n);
      const float r = convex || i % 2 == 0 ? 1.0f : 0.9f;
      f << "v " << r * std::cos(a) << " " << r * std::sin(a) << " 0\n";
    }
    f << "f";
    for (int i = 1; i <= n; ++i) f << " " << i;
    f << "\n";
    f.close();
    const Scene s = loadScene(path);
    size_t tris = 0;
    for (const Mesh& m : s.meshes) tris += m.triangleCount();
    EXPECT_EQ(tris + s.stats.degenerateTriangles, size_t(n - 2)) << path;
    EXPECT_GT(tris, size_t(n / 2)) << path;
  }
}
