// glTF features beyond plain indexed triangles, on the robustness corpus' small files:
// strips and fans (winding kept), sparse accessors, Draco-compressed meshes (equal to the mesh
// they were encoded from), the occlusion texture (ambient term only) and glTF 1.0 named.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"
#include "scene/loaders.h"
#include "test_util.h"

namespace tandem {
namespace {

std::string corpusFile(const std::string& name) {
  return std::string(TANDEM_SOURCE_DIR) + "/tests/data/robustness/" + name;
}

Vec3 triangleNormal(const Mesh& m, size_t t) {
  const Vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
             c = m.positions[m.indices[3 * t + 2]];
  return cross(b - a, c - a);
}

double totalArea(const Mesh& m) {
  double a = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) a += 0.5 * length(triangleNormal(m, t));
  return a;
}

TEST(GltfTopology, StripAndFanBecomeConsistentlyWoundTriangles) {
  // A unit quad as a 4-vertex strip: two triangles, both facing +z (counter-clockwise).
  Scene strip = loadScene(corpusFile("strip.gltf"));
  ASSERT_EQ(strip.meshes.size(), 1u);
  ASSERT_EQ(strip.meshes[0].triangleCount(), 2u);
  for (size_t t = 0; t < 2; ++t) EXPECT_GT(triangleNormal(strip.meshes[0], t).z, 0.0f);
  EXPECT_NEAR(totalArea(strip.meshes[0]), 1.0, 1e-6);
  // A regular hexagon as a fan around its centre: six triangles, area 3 sqrt(3) / 2.
  Scene fan = loadScene(corpusFile("fan.gltf"));
  ASSERT_EQ(fan.meshes[0].triangleCount(), 6u);
  for (size_t t = 0; t < 6; ++t) EXPECT_GT(triangleNormal(fan.meshes[0], t).z, 0.0f);
  EXPECT_NEAR(totalArea(fan.meshes[0]), 1.5 * std::sqrt(3.0), 1e-5);
}

TEST(GltfTopology, PointsAndLinesAreSkipped) {
  Scene s = loadScene(corpusFile("lines_and_triangles.gltf"));
  EXPECT_EQ(s.stats.skippedPrimitives, 1u);
  EXPECT_EQ(s.triangleCount(), 1u);
  try {
    loadScene(corpusFile("points_only.gltf"));
    FAIL() << "a file of points only loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("1 point or line primitives skipped"), std::string::npos);
  }
}

TEST(GltfSparse, SubstitutionsApplyOverDataAndOverZeros) {
  // Vertex 3 of the flat quad is lifted to z = 0.5 by the sparse values.
  Scene s = loadScene(corpusFile("sparse.gltf"));
  const Mesh& m = s.meshes[0];
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[0].z, 0.0f);
  EXPECT_EQ(m.positions[3].x, 1.0f);
  EXPECT_EQ(m.positions[3].z, 0.5f);
  // No bufferView: zeros, then vertices 1 and 2 set to (1,0,0) and (0,1,0).
  Scene z = loadScene(corpusFile("sparse_no_bufferview.gltf"));
  const Mesh& t = z.meshes[0];
  ASSERT_EQ(t.positions.size(), 3u);
  EXPECT_EQ(length(t.positions[0]), 0.0f);
  EXPECT_EQ(t.positions[1].x, 1.0f);
  EXPECT_EQ(t.positions[2].y, 1.0f);
}

TEST(GltfDraco, DecodesToTheMeshItWasEncodedFrom) {
  // draco_cube.gltf holds draco_cube_source.obj encoded losslessly; the node rotates it.
  Scene d = loadScene(corpusFile("draco_cube.gltf"));
  Scene o = loadScene(corpusFile("draco_cube_source.obj"));
  ASSERT_EQ(d.meshes.size(), 1u);
  const Mesh& dm = d.meshes[0];
  EXPECT_EQ(dm.triangleCount(), o.triangleCount());
  EXPECT_EQ(dm.uvs.size(), dm.positions.size());
  EXPECT_EQ(dm.normals.size(), dm.positions.size());
  EXPECT_NEAR(totalArea(dm), 24.0, 1e-4);  // a 2 x 2 x 2 cube
  // The same set of corner positions (object space: the rotation is in the node).
  for (const Vec3& p : dm.positions)
    EXPECT_NEAR(std::abs(p.x) + std::abs(p.y) + std::abs(p.z), 3.0f, 1e-5f);
  // Face normals agree with the decoded vertex normals (outward, unit).
  for (size_t t = 0; t < dm.triangleCount(); ++t) {
    const Vec3 n = normalize(triangleNormal(dm, t));
    EXPECT_GT(dot(n, dm.normals[dm.indices[3 * t]]), 0.999f);
  }
  EXPECT_THROW(loadScene(corpusFile("draco_wrong_attribute_id.gltf")), InputError);
  EXPECT_THROW(loadScene(corpusFile("draco_truncated.gltf")), InputError);
}

TEST(GltfOcclusion, DarkensTheAmbientTermOnly) {
  // The quad's occlusion texture is a checker of 1.0 and 40/255; lit by ambient alone the
  // image shows the checker, lit by a sun alone it does not.
  Scene s = loadScene(corpusFile("occlusion.gltf"));
  ASSERT_GE(s.materials[0].occlusionTexture, 0);
  s.ambient = {1, 1, 1};
  s.skybox.color = {0, 0, 0};
  CameraDesc cam;
  cam.position = {0.5f, 0.5f, 1.6f};
  cam.lookAt = {0.5f, 0.5f, 0.0f};
  cam.vfovDeg = 30;
  auto contrast = [&](const Scene& sc) {
    const Buffer img = test::renderHdr(sc, "deferred", cam, {}, 0.0f, 64, 64);
    float lo = 1e9f, hi = 0;
    for (int y = 24; y < 40; ++y)
      for (int x = 24; x < 40; ++x) {
        const float l = luminance(img.rgb(x, y));
        lo = std::min(lo, l), hi = std::max(hi, l);
      }
    return std::pair(lo, hi);
  };
  const auto [lo, hi] = contrast(s);
  EXPECT_GT(hi, 0.5f);
  EXPECT_LT(lo / hi, 0.3f) << "occluded texels darken the ambient term";
  Scene sun = s;
  sun.ambient = {0, 0, 0};
  Light l;
  l.type = LightType::Directional;
  l.direction = {0, 0, -1};
  l.intensity = 3;
  sun.lights.push_back(l);
  const auto [slo, shi] = contrast(sun);
  EXPECT_GT(shi, 0.3f);
  EXPECT_GT(slo / shi, 0.95f) << "direct light ignores occlusion";
}

TEST(GltfVersion, GltfOneIsNamed) {
  for (const char* f : {"gltf1.gltf", "gltf1_no_asset.gltf", "gltf1.glb"}) {
    try {
      loadScene(corpusFile(f));
      FAIL() << f << " loaded";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("glTF 1.0 is not supported"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace tandem

namespace tandem {
namespace {

// Two unit quads side by side in z = 0 sharing the edge x = 1; the right one's u runs backwards
// (a mirrored UV island, as symmetric models have).
Mesh mirroredQuads() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}, {0, 1}};
  m.normals.assign(6, Vec3(0, 0, 1));
  m.indices = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
  return m;
}

TEST(MikkTSpaceTangents, FollowDPduAndSplitMirroredVertices) {
  Mesh m = mirroredQuads();
  computeMikkTSpaceTangents(m);
  ASSERT_EQ(m.positions.size(), 8u) << "the two shared vertices are split";
  ASSERT_EQ(m.tangents.size(), m.positions.size());
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* i = &m.indices[3 * t];
    const bool mirrored = t >= 2;
    for (int k = 0; k < 3; ++k) {
      const Vec4 tg = m.tangents[i[k]];
      // T along dP/du (+x on the left, -x on the mirrored right), w the orientation, and the
      // bitangent w * cross(n, t) along dP/dv (+y) on both.
      EXPECT_NEAR(tg.x, mirrored ? -1.0f : 1.0f, 1e-6f);
      EXPECT_EQ(tg.w, mirrored ? -1.0f : 1.0f);
      const Vec3 b = cross(m.normals[i[k]], Vec3(tg.x, tg.y, tg.z)) * tg.w;
      EXPECT_NEAR(b.y, 1.0f, 1e-6f);
    }
  }
}

TEST(MikkTSpaceTangents, UnitOrthogonalAndAlongDPduOnACurvedMesh) {
  Mesh m = makeUvSphere(24, 12);
  computeMikkTSpaceTangents(m);
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* i = &m.indices[3 * t];
    const Vec3 e1 = m.positions[i[1]] - m.positions[i[0]],
               e2 = m.positions[i[2]] - m.positions[i[0]];
    const Vec2 d1 = m.uvs[i[1]] - m.uvs[i[0]], d2 = m.uvs[i[2]] - m.uvs[i[0]];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-12f) continue;
    const Vec3 dPdu = (e1 * d2.y - e2 * d1.y) * (1.0f / det);
    for (int k = 0; k < 3; ++k) {
      const Vec4 tg = m.tangents[i[k]];
      const Vec3 t3(tg.x, tg.y, tg.z), n = m.normals[i[k]];
      EXPECT_NEAR(length(t3), 1.0f, 1e-4f);
      EXPECT_NEAR(dot(t3, n), 0.0f, 1e-4f);
      if (std::abs(dot(n, Vec3(0, 1, 0))) < 0.9f) {  // away from the poles' fans
        EXPECT_GT(dot(t3, normalize(dPdu)), 0.8f);
      }
    }
  }
}

}  // namespace
}  // namespace tandem
