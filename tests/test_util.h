// Shared helpers for tests: paths to the third-party scenes and a scratch folder.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/assets.h"
#include "pipeline/renderer.h"
#include "scene/primitives.h"

namespace tandem::test {

// A third-party scene file under TANDEM_ASSETS (default ../shared/scenes beside the checkout).
inline std::string assetPath(const std::string& rel) {
  return assetsDir() + "/" + rel;
}

// Declares `var` as the path of the third-party file `rel`, or skips the test, saying why, when
// the file is not there (a clone with nothing beside it).
#define TANDEM_ASSET(var, rel)                                                                  \
  const std::string var = ::tandem::test::assetPath(rel);                                       \
  if (!std::filesystem::exists(var))                                                            \
  GTEST_SKIP() << "third-party asset " << var << " not found (set TANDEM_ASSETS to the folder " \
               << "of third-party scenes)"

// A fresh empty folder under the build tree for one test.
inline std::filesystem::path scratchDir(const std::string& name) {
  std::filesystem::path p = std::filesystem::path(TANDEM_TEST_SCRATCH) / name;
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

inline void writeText(const std::filesystem::path& p, const std::string& text) {
  FILE* f = std::fopen(p.string().c_str(), "wb");
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
}

// Renders one frame of `scene` through a built-in pipeline and returns the renderer.
inline std::unique_ptr<Renderer> renderOnce(const Scene& scene, const std::string& pipeline, int w,
                                            int h, const CameraDesc& cam, Vec2 jitter = {0, 0}) {
  auto r = std::make_unique<Renderer>(scene, Pipeline::load(pipeline),
                                      RenderSettings{.width = w, .height = h});
  r->renderFrame(0, cam, jitter);
  return r;
}

// Renders one frame (96 x 64 unless given) of `scene` through a built-in pipeline with pass
// parameters `sets` ("pass.param=value") and returns its hdr buffer.
inline Buffer renderHdr(const Scene& s, const std::string& pipeline, const CameraDesc& cam,
                        const std::vector<std::string>& sets, float shutter = 0.0f, int w = 96,
                        int h = 64) {
  Pipeline p = Pipeline::load(pipeline);
  for (const std::string& a : sets) p.setParam(a, "test");
  Renderer r(s, std::move(p), RenderSettings{.width = w, .height = h, .shutter = shutter});
  r.renderFrame(0, cam);
  return r.context().input("hdr");
}

// Unlit emissive squares (radiance (1, 0.8, 0.6), 1 x 1 m) at 4, 6 and 8 m in front of a camera at
// z = 2 looking down -z, over a black sky: rasterized emission and path-traced emission are the
// same light transport whatever the shading model, so images differ only by how visibility,
// depth of field and motion blur are sampled. Object i is at x = i - 1, y = 0.3 (i - 1).
inline Scene emissiveSquares() {
  Scene s;
  Material m;
  m.diffuse = m.specular = {0, 0, 0};
  m.emission = {1, 0.8f, 0.6f};
  m.doubleSided = true;
  const int mat = s.addMaterial(m), mesh = s.addMesh(makePlane());
  for (int i = 0; i < 3; ++i) {
    Transform xf;
    xf.position = {-1.0f + 1.0f * float(i), 0.3f * float(i - 1), -2.0f - 2.0f * float(i)};
    xf.rotationDeg = {90, 0, 0};  // facing the camera (+z)
    xf.scale = {0.5f, 1, 0.5f};
    s.addObject("square" + std::to_string(i), mesh, mat, xf);
  }
  s.skybox.color = {0, 0, 0};
  return s;
}

}  // namespace tandem::test
