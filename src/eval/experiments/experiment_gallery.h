// `tandem experiment demo` (runner "gallery"): what Tandem is for, in one picture. Each row
// renders one scene through a technique's baseline, its hybrid and its fully ray-traced
// counterpart, each for a few frames of a still camera (temporal passes converge; the first
// frame, which builds the BVH and probes, is not timed), next to the row's ground truth: a
// reference render of the same light transport (`tandem reference` with the row's integrator,
// lens, shutter and stereo pair, cached) or, without one, the row's fully ray-traced image. It
// writes every image, a labelled contact sheet (contact_sheet.png: pipeline, median ms per frame
// and the error against the ground truth under each picture) and index.html with the table.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tandem {

struct GalleryEntry {
  std::string pipeline, caption;
  std::vector<std::string> sets;  // "pass.param=value", as --set
  std::string overlay;            // a buffer drawn translucently over the picture (e.g. fov_layer)
};

// The row's ground truth rendered by the reference path tracer (integrator "" = none: the row's
// `reference` pipeline is its ground truth).
struct GalleryGroundTruth {
  std::string integrator;  // whitted | diffuse-gi | path
  int spp = 64;
  std::string caption = "Ground truth";
};

struct GalleryRow {
  std::string label, scene;
  std::vector<GalleryEntry> pipelines;
  int reference = -1;   // without a ground truth: the pipeline compared with (-1: the last)
  int frames = 0;       // 0: the gallery's
  float shutter = 0;    // seconds the shutter stays open (motion blur)
  bool stereo = false;  // render the scene's stereo pair; the sheet shows the left eye
  GalleryGroundTruth groundTruth;
};

struct GalleryOptions {
  std::string out = "out/demo";
  std::string title = "Tandem";
  std::string cache;  // reference cache folder ("" = none)
  int width = 640, height = 360;
  int frames = 8;  // per image; the median of frames 2..N is the time shown
  int threads = 0;
  std::vector<GalleryRow> rows;
};

GalleryOptions galleryOptionsFromJson(const nlohmann::json& j, const std::string& file);
int runGallery(const GalleryOptions& o);

}  // namespace tandem
