// `tandem experiment demo` (runner "gallery"): what Tandem is for, in one picture. Each row
// renders one scene through a cheap pipeline, a hybrid one and its fully ray-traced counterpart
// (e.g. deferred / hybrid-heuristic-taa / rt-only, postfx-dof / hybrid-dof / rt-dof), each for a
// few frames of a still camera (temporal passes converge; the first frame, which builds the
// BVH and probes, is not timed), and writes every image, a labelled contact sheet
// (contact_sheet.png: pipeline and median ms per frame under each picture), and index.html with a
// table of frame times and each image's PSNR / SSIM against the row's ray-traced image (the same
// shading fully ray traced: the difference is what the cheaper pipeline leaves out).
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tandem {

struct GalleryRow {
  std::string label, scene;
  std::vector<std::pair<std::string, std::string>> pipelines;  // pipeline, caption
  int reference = -1;  // index of the pipeline the others are compared with (-1: the last)
  int frames = 0;      // 0: the gallery's
};

struct GalleryOptions {
  std::string out = "out/demo";
  std::string title = "Tandem";
  int width = 640, height = 360;
  int frames = 8;  // per image; the median of frames 2..N is the time shown
  int threads = 0;
  std::vector<GalleryRow> rows;
};

GalleryOptions galleryOptionsFromJson(const nlohmann::json& j, const std::string& file);
int runGallery(const GalleryOptions& o);

}  // namespace tandem
