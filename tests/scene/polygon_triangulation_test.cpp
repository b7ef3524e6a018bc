// Polygons of any size triangulate in bounded time into n - 2 triangles that tile the polygon:
// no gaps, no overlaps (their areas add up to the polygon's, all wound like it), and OBJ faces of
// 100k vertices load.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/error.h"
#include "core/image_io.h"
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
  // Large non-convex polygons are ear-clipped too (reflex vertices looked up in a grid), not
  // fanned: a fan of a star overlaps itself and leaves gaps.
  expectTiling(star(2000, 0.7f, false));
  expectTiling(star(50000, 0.9f, true));
  // Collinear vertices along the edges of a non-convex polygon.
  std::vector<Vec3> comb;
  for (int i = 0; i <= 100; ++i) comb.push_back({float(i) * 0.01f, 0, 0});
  for (int i = 0; i < 20; ++i) {
    const float x = 1.0f - float(i) * 0.05f;
    comb.push_back({x, 1, 0});
    comb.push_back({x - 0.025f, 0.5f, 0});
  }
  expectTiling(comb);
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

// A face of 100k vertices (tinyobjloader's triangulation took minutes) and a large non-convex
// one load, every vertex kept.
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

// Text encodings and Windows paths: a UTF-8 byte-order mark, UTF-16 of either byte order, and an
// MTL texture written ".\name.png" load like the plain file.
TEST(ObjLoader, ByteOrderMarksAndWindowsTexturePaths) {
  const auto dir = test::scratchDir("obj_encodings");
  const std::string body =
      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "usemtl wood\nf 1/1 2/2 3/3 4/4\n";
  {
    std::ofstream m(dir / "m.mtl");
    m << "newmtl wood\nKd 1 1 1\nmap_Kd .\\wood.png\n";
    Buffer tex(2, 2, 3, 0.5f);
    writePng((dir / "wood.png").string(), tex);
  }
  auto write = [&](const std::string& name, const std::string& bytes) {
    std::ofstream f(dir / name, std::ios::binary);
    f << bytes;
    return (dir / name).string();
  };
  std::string le = "\xFF\xFE", be = "\xFE\xFF";
  for (char c : body) {
    le += c, le += '\0';
    be += '\0', be += c;
  }
  for (const std::string& path : {write("plain.obj", body), write("bom.obj", "\xEF\xBB\xBF" + body),
                                  write("le.obj", le), write("be.obj", be)}) {
    const Scene s = loadScene(path);
    size_t tris = 0;
    for (const Mesh& m : s.meshes) tris += m.triangleCount();
    EXPECT_EQ(tris, 2u) << path;
    ASSERT_FALSE(s.materials.empty()) << path;
    EXPECT_GE(s.materials.back().diffuseTexture, 0) << path << ": the texture was not found";
  }
  const char wideBytes[] = "\xFF\xFEv\0 \0\xE9\0";  // UTF-16 "v é": beyond ASCII
  const std::string wide(wideBytes, sizeof wideBytes - 1);
  try {
    loadScene(write("wide.obj", wide));
    ADD_FAILURE() << "no error for UTF-16 beyond ASCII";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("UTF-16"), std::string::npos) << e.what();
  }
}
