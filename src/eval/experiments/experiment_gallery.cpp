#include "eval/experiments/experiment_gallery.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/bitmap_font.h"
#include "core/file_commit.h"
#include "core/image_io.h"
#include "core/json_fields.h"
#include "eval/experiments/experiment_report.h"
#include "eval/metrics/metrics.h"
#include "eval/reference/reference_cache.h"
#include "pipeline/aov.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace fs = std::filesystem;

namespace {

// [pipeline, caption] or {"pipeline", "caption", "set": [...], "overlay": buffer}.
GalleryEntry entryFromJson(const Json& x, JsonFields& row, const std::string& file,
                           const std::string& where) {
  GalleryEntry e;
  if (x.is_array()) {
    if (x.size() != 2 || !x[0].is_string() || !x[1].is_string())
      row.fail("pipelines", "each entry is [pipeline, caption] or an object");
    e.pipeline = x[0].get<std::string>();
    e.caption = x[1].get<std::string>();
    return e;
  }
  JsonFields f(x, file, where);
  e.pipeline = f.string("pipeline", "");
  if (e.pipeline.empty()) f.fail("pipeline", "names the pipeline to render");
  e.caption = f.string("caption", e.pipeline);
  e.overlay = f.string("overlay", "");
  if (f.has("set")) {
    const Json& s = f.raw("set");
    if (!s.is_array()) f.fail("set", "expected an array of \"pass.param=value\" strings");
    for (const Json& v : s) {
      if (!v.is_string()) f.fail("set", "expected an array of \"pass.param=value\" strings");
      e.sets.push_back(v.get<std::string>());
    }
  }
  f.finish();
  return e;
}

GalleryGroundTruth groundTruthFromJson(const Json& j, const std::string& file,
                                       const std::string& where) {
  JsonFields f(j, file, where);
  GalleryGroundTruth g;
  g.integrator = f.string("integrator", "whitted");
  if (g.integrator != "whitted" && g.integrator != "diffuse-gi" && g.integrator != "path")
    f.fail("integrator", "expected whitted, diffuse-gi or path");
  g.spp = f.integer("spp", g.spp, 1, 1 << 20);
  g.caption = f.string("caption", g.caption);
  f.finish();
  return g;
}

GalleryRow rowFromJson(const Json& j, const std::string& file, size_t i) {
  const std::string where = "rows[" + std::to_string(i) + "]";
  JsonFields r(j, file, where);
  GalleryRow row;
  row.label = r.string("label", "row " + std::to_string(i));
  row.scene = r.string("scene", "cornell");
  // A relative scene file is taken from the gallery file's folder (built-in names as they are).
  if (row.scene.find('.') != std::string::npos && fs::path(row.scene).is_relative())
    row.scene = (fs::path(file).parent_path() / row.scene).lexically_normal().string();
  row.frames = r.integer("frames", 0, 0, 10000);
  row.shutter = r.number("shutter", 0.0f, 0.0f, 10.0f);
  row.stereo = r.boolean("stereo", false);
  const Json& p = r.raw("pipelines");
  if (!p.is_array() || p.empty())
    r.fail("pipelines", "expected [[pipeline, caption], ...] (at least one)");
  for (size_t k = 0; k < p.size(); ++k)
    row.pipelines.push_back(
        entryFromJson(p[k], r, file, where + ".pipelines[" + std::to_string(k) + "]"));
  if (r.has("groundTruth"))
    row.groundTruth = groundTruthFromJson(r.raw("groundTruth"), file, where + ".groundTruth");
  row.reference = r.integer("reference", -1, -1, int(row.pipelines.size()) - 1);
  r.finish();
  return row;
}

}  // namespace

GalleryOptions galleryOptionsFromJson(const nlohmann::json& j, const std::string& file) {
  JsonFields f(j, file, "");
  GalleryOptions o;
  f.string("runner", "gallery");
  o.title = f.string("title", o.title);
  o.width = f.integer("width", o.width, 16, 16384);
  o.height = f.integer("height", o.height, 16, 16384);
  o.frames = f.integer("frames", o.frames, 2, 10000);
  if (!f.has("rows")) f.fail("rows", "a gallery needs rows");
  const Json& rows = f.raw("rows");
  if (!rows.is_array() || rows.empty()) f.fail("rows", "expected a non-empty array of rows");
  for (size_t i = 0; i < rows.size(); ++i) o.rows.push_back(rowFromJson(rows[i], file, i));
  f.finish();
  return o;
}

namespace {

struct Cell {
  std::string pipeline, caption, file, timing;
  Buffer image;  // display space, the left eye of a stereo pair: what errors are measured on
  Buffer shown;  // what the sheet and the PNG show: the image with the overlay
  double ms = 0;
  ImageMetrics error;
  bool isGroundTruth = false;
};

RenderSettings rowSettings(const GalleryRow& row, const Scene& scene, int w, int h) {
  RenderSettings rs{.width = w, .height = h, .shutter = row.shutter};
  if (row.stereo) {
    rs.stereo = scene.stereo;
    rs.stereo.enabled = true;
  }
  return rs;
}

// The left `w` columns of a side-by-side stereo image (the whole image otherwise).
Buffer leftEye(const Buffer& b, int w) {
  if (b.width == w) return b;
  Buffer out(w, b.height, b.channels);
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < b.channels; ++k) out.at(x, y)[k] = b.at(x, y)[k];
  return out;
}

// Renders `frames` frames of a still camera; the median frame time excludes the first frame.
Cell renderCell(const Scene& scene, const CameraDesc& cam, const GalleryEntry& e,
                const RenderSettings& rs, int frames) {
  Pipeline p = Pipeline::load(e.pipeline);
  for (const std::string& s : e.sets) p.setParam(s, "gallery");
  Renderer r(scene, std::move(p), rs);
  r.keepOnDevice();  // timed: the picture read back after the frames
  std::vector<double> ms;
  for (int i = 0; i < frames; ++i) {
    const FrameTimings t = r.renderFrame(0, cam);
    if (i > 0) ms.push_back(t.totalMs);
  }
  Cell c;
  c.pipeline = e.pipeline;
  c.caption = e.caption;
  c.image = leftEye(r.output(), rs.width);
  c.ms = summarize(ms).median;
  char timing[64];
  std::snprintf(timing, sizeof timing, "%.1f MS / FRAME", c.ms);
  c.timing = timing;
  c.shown = c.image;
  if (!e.overlay.empty()) {  // the buffer's visualisation over the picture, a third opaque
    const Buffer ov = leftEye(visualizeBuffer(r.fetch(e.overlay)), rs.width);
    for (int y = 0; y < c.shown.height; ++y)
      for (int x = 0; x < c.shown.width; ++x)
        for (int k = 0; k < std::min(3, c.shown.channels); ++k)
          c.shown.at(x, y)[k] =
              0.67f * c.shown.at(x, y)[k] + 0.33f * ov.at(x, y)[std::min(k, ov.channels - 1)];
  }
  return c;
}

// The row's ground truth: the reference path tracer with the row's integrator, the camera's lens
// and the shutter (the left eye's camera for a stereo row), from the cache when rendered before.
Cell groundTruthCell(const GalleryRow& row, const Scene& scene, const CameraDesc& cam,
                     const RenderSettings& rs, const std::string& cache) {
  ReferenceJob job;
  job.scene = &scene;
  job.camera = job.shutterCamera = eyeCamera(cam, rs.stereo, 0);
  job.shutter = row.shutter;
  job.width = rs.width;
  job.height = rs.height;
  job.settings.spp = row.groundTruth.spp;
  job.settings.integrator = row.groundTruth.integrator == "whitted"      ? Integrator::Whitted
                            : row.groundTruth.integrator == "diffuse-gi" ? Integrator::DiffuseGI
                                                                         : Integrator::Path;
  job.settings.progress = true;
  const ReferenceImage ref = referenceImage(job, cache);
  Cell c;
  c.pipeline = "reference";
  c.caption = row.groundTruth.caption;
  c.image = c.shown = visualizeBuffer(ref.hdr);
  c.ms = ref.seconds * 1000.0;
  c.timing = row.groundTruth.integrator + " " + std::to_string(ref.spp) + " SPP" +
             (ref.fromCache ? " (CACHED)" : "");
  c.isGroundTruth = true;
  return c;
}

std::string errorLine(const Cell& c) {
  if (c.isGroundTruth) return "GROUND TRUTH";
  char s[96];
  std::snprintf(s, sizeof s, "SSIM %.3f  PSNR %.1f DB", c.error.ssim, c.error.psnr);
  return s;
}

// The contact sheet: rows of pictures, each with three caption lines under it.
Buffer contactSheet(const std::vector<std::vector<Cell>>& rows, const std::vector<GalleryRow>& spec,
                    int w, int h) {
  const int scale = w >= 480 ? 2 : 1, pad = 4 * scale, line = kGlyphHeight * scale + pad;
  const int bar = line * 3 + pad * 3;
  const int titleBar = kGlyphHeight * scale + pad * 2;
  size_t cols = 0;
  for (const auto& r : rows) cols = std::max(cols, r.size());
  Buffer sheet(int(cols) * (w + pad) + pad, int(rows.size()) * (h + bar + titleBar) + pad, 3,
               0.08f);
  const Vec3 text(0.92f), dim(0.65f);
  for (size_t ri = 0; ri < rows.size(); ++ri) {
    const int top = int(ri) * (h + bar + titleBar) + pad;
    drawText(sheet, pad, top + pad / 2, spec[ri].label, text, scale);
    for (size_t ci = 0; ci < rows[ri].size(); ++ci) {
      const Cell& c = rows[ri][ci];
      const int x0 = pad + int(ci) * (w + pad), y0 = top + titleBar;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int k = 0; k < 3; ++k)
            sheet.at(x0 + x, y0 + y)[k] = c.shown.at(x, y)[std::min(k, c.shown.channels - 1)];
      drawText(sheet, x0, y0 + h + pad, c.caption, text, scale);
      drawText(sheet, x0, y0 + h + pad + line, c.pipeline + "  " + c.timing, dim, scale);
      drawText(sheet, x0, y0 + h + pad + 2 * line, errorLine(c), dim, scale);
    }
  }
  return sheet;
}

// Renders a row's cells (and its ground truth) and measures each against the ground truth.
std::vector<Cell> renderRow(const GalleryRow& row, const Scene& scene, const GalleryOptions& o) {
  const CameraDesc cam = defaultCamera(scene);
  const RenderSettings rs = rowSettings(row, scene, o.width, o.height);
  const int frames = row.frames > 0 ? row.frames : o.frames;
  std::vector<Cell> cells;
  for (const GalleryEntry& e : row.pipelines) {
    std::printf("demo: %s: %s (%d frames)\n", row.label.c_str(), e.pipeline.c_str(), frames);
    std::fflush(stdout);
    cells.push_back(renderCell(scene, cam, e, rs, frames));
  }
  size_t truth = row.reference >= 0 ? size_t(row.reference) : cells.size() - 1;
  if (!row.groundTruth.integrator.empty()) {
    std::printf("demo: %s: ground truth (%s, %d spp)\n", row.label.c_str(),
                row.groundTruth.integrator.c_str(), row.groundTruth.spp);
    std::fflush(stdout);
    cells.push_back(groundTruthCell(row, scene, cam, rs, o.cache));
    truth = cells.size() - 1;
  }
  cells[truth].isGroundTruth = true;
  for (Cell& c : cells) {
    c.file = sceneLabel(row.scene) + "_" + c.pipeline + ".png";
    if (!c.isGroundTruth) c.error = compareImages(c.image, cells[truth].image);
  }
  return cells;
}

}  // namespace

int runGallery(const GalleryOptions& o) {
  // Every scene and pipeline is checked before anything is rendered or written.
  std::vector<Scene> scenes;
  for (const GalleryRow& r : o.rows) {
    scenes.push_back(loadScene(r.scene));
    for (const GalleryEntry& e : r.pipelines) {
      Pipeline p = Pipeline::load(e.pipeline);
      for (const std::string& s : e.sets) p.setParam(s, "gallery");
      const std::vector<std::string> produced = p.producedBuffers();
      if (!e.overlay.empty() &&
          std::find(produced.begin(), produced.end(), e.overlay) == produced.end())
        throw InputError("gallery", "overlay",
                         "pipeline '" + e.pipeline + "' has no buffer '" + e.overlay + "'");
    }
  }
  fs::create_directories(o.out);
  ExperimentReport report(o.out, o.title);
  std::vector<std::vector<Cell>> cells;
  std::vector<std::vector<std::string>> table;
  FileCommit files;
  for (size_t ri = 0; ri < o.rows.size(); ++ri) {
    const GalleryRow& row = o.rows[ri];
    cells.push_back(renderRow(row, scenes[ri], o));
    const Cell& truth = *std::find_if(cells.back().begin(), cells.back().end(),
                                      [](const Cell& c) { return c.isGroundTruth; });
    for (const Cell& c : cells.back()) {
      table.push_back(
          {row.label, c.caption, c.pipeline, c.isGroundTruth ? "" : fmt(c.ms, 1),
           c.isGroundTruth ? "(ground truth: " + truth.timing + ")" : fmt(c.error.psnr, 1),
           c.isGroundTruth ? "" : fmt(c.error.ssim, 4),
           c.isGroundTruth ? "" : fmt(c.error.rmse, 4)});
      files.stage((fs::path(o.out) / c.file).string(), encodePng(c.file, c.shown));
      report.image(c.file, row.label + ": " + c.caption + " (" + c.pipeline + ", " + c.timing +
                               (c.isGroundTruth ? "" : ", " + errorLine(c)) + ")");
    }
  }
  const Buffer sheet = contactSheet(cells, o.rows, o.width, o.height);
  files.stage((fs::path(o.out) / "contact_sheet.png").string(), encodePng("contact_sheet", sheet));
  files.commit();
  report.image("contact_sheet.png",
               "All rows, labelled with pipeline, median ms per frame and error against the row's "
               "ground truth");
  report.markdown(
      "Each image: " + std::to_string(o.frames) +
      " frames (unless the row says otherwise) of a "
      "still camera at " +
      std::to_string(o.width) + "x" + std::to_string(o.height) +
      " per eye (temporal passes converge); the time is the median frame after the first (which "
      "builds the BVH and probes). PSNR, SSIM and RMSE compare each image with its row's ground "
      "truth: the reference path tracer with the same light transport (Whitted shading with the "
      "lens or shutter of the row; the diffuse path tracer for foveation), so the difference is "
      "what the cheaper pipeline leaves out or gets wrong. Stereo rows render both eyes and "
      "show and measure the left one.\n\n");
  report.table(
      "demo", {"row", "image", "pipeline", "ms / frame", "PSNR dB vs ground truth", "SSIM", "RMSE"},
      table);
  report.write("width " + std::to_string(o.width) + ", height " + std::to_string(o.height) +
               ", frames " + std::to_string(o.frames));
  return 0;
}

}  // namespace tandem
