// Shared helpers for tests: paths to the third-party scenes and a scratch folder.
#pragma once
#include <filesystem>
#include <string>

#include "pipeline/renderer.h"

namespace tandem::test {

inline std::string sharedScene(const std::string& rel) {
  return std::string(TANDEM_SHARED_SCENES) + "/" + rel;
}

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

}  // namespace tandem::test
