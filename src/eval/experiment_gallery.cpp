#include "eval/experiment_gallery.h"

#include <cstdio>
#include <filesystem>

#include "core/bitmap_font.h"
#include "core/file_commit.h"
#include "core/image_io.h"
#include "core/json_fields.h"
#include "eval/experiment_report.h"
#include "eval/metrics.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace fs = std::filesystem;

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
  const fs::path base = fs::path(file).parent_path();
  for (size_t i = 0; i < rows.size(); ++i) {
    JsonFields r(rows[i], file, "rows[" + std::to_string(i) + "]");
    GalleryRow row;
    row.label = r.string("label", "row " + std::to_string(i));
    row.scene = r.string("scene", "cornell");
    // A relative scene file is taken from the gallery file's folder (built-in names as they are).
    if (row.scene.find('.') != std::string::npos && fs::path(row.scene).is_relative())
      row.scene = (base / row.scene).lexically_normal().string();
    row.frames = r.integer("frames", 0, 0, 10000);
    const Json& p = r.raw("pipelines");
    if (!p.is_array() || p.empty())
      r.fail("pipelines", "expected [[pipeline, caption], ...] (at least one)");
    for (const Json& x : p) {
      if (!x.is_array() || x.size() != 2 || !x[0].is_string() || !x[1].is_string())
        r.fail("pipelines", "each entry is [pipeline, caption]");
      row.pipelines.push_back({x[0].get<std::string>(), x[1].get<std::string>()});
    }
    row.reference = r.integer("reference", -1, -1, int(row.pipelines.size()) - 1);
    r.finish();
    o.rows.push_back(row);
  }
  f.finish();
  return o;
}

namespace {

struct Cell {
  std::string pipeline, caption, file;
  Buffer image;  // display space
  double ms = 0;
};

// Renders `frames` frames of a still camera; the median frame time excludes the first frame.
Cell renderCell(const Scene& scene, const CameraDesc& cam, const std::string& pipeline,
                const RenderSettings& rs, int frames) {
  Renderer r(scene, Pipeline::load(pipeline), rs);
  std::vector<double> ms;
  for (int i = 0; i < frames; ++i) {
    const FrameTimings t = r.renderFrame(0, cam);
    if (i > 0) ms.push_back(t.totalMs);
  }
  Cell c;
  c.pipeline = pipeline;
  c.image = r.output();
  c.ms = summarize(ms).median;
  return c;
}

// The contact sheet: rows of pictures, each with a caption bar under it.
Buffer contactSheet(const std::vector<std::vector<Cell>>& rows, const std::vector<GalleryRow>& spec,
                    int w, int h) {
  const int scale = w >= 480 ? 2 : 1, pad = 4 * scale;
  const int bar = kGlyphHeight * scale * 2 + pad * 6;  // two caption lines, then a gap
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
            sheet.data[(size_t(y0 + y) * size_t(sheet.width) + size_t(x0 + x)) * 3 + size_t(k)] =
                c.image.data[(size_t(y) * size_t(w) + size_t(x)) * size_t(c.image.channels) +
                             size_t(std::min(k, c.image.channels - 1))];
      char ms[64];
      std::snprintf(ms, sizeof ms, "%.1f MS / FRAME", c.ms);
      drawText(sheet, x0, y0 + h + pad, c.caption, text, scale);
      drawText(sheet, x0, y0 + h + pad * 2 + kGlyphHeight * scale, c.pipeline + "  " + ms, dim,
               scale);
    }
  }
  return sheet;
}

}  // namespace

int runGallery(const GalleryOptions& o) {
  // Every scene and pipeline is checked before anything is rendered or written.
  std::vector<Scene> scenes;
  for (const GalleryRow& r : o.rows) {
    scenes.push_back(loadScene(r.scene));
    for (const auto& p : r.pipelines) Pipeline::load(p.first);
  }
  fs::create_directories(o.out);
  ExperimentReport report(o.out, o.title);
  const RenderSettings rs{.width = o.width, .height = o.height};
  std::vector<std::vector<Cell>> cells(o.rows.size());
  std::vector<std::vector<std::string>> table;
  FileCommit files;
  for (size_t ri = 0; ri < o.rows.size(); ++ri) {
    const GalleryRow& row = o.rows[ri];
    const CameraDesc cam = defaultCamera(scenes[ri]);
    const int frames = row.frames > 0 ? row.frames : o.frames;
    for (const auto& [pipeline, caption] : row.pipelines) {
      std::printf("demo: %s: %s (%d frames)\n", row.label.c_str(), pipeline.c_str(), frames);
      std::fflush(stdout);
      Cell c = renderCell(scenes[ri], cam, pipeline, rs, frames);
      c.caption = caption;
      c.file = sceneLabel(row.scene) + "_" + pipeline + ".png";
      cells[ri].push_back(std::move(c));
    }
    const size_t ref = row.reference >= 0 ? size_t(row.reference) : row.pipelines.size() - 1;
    for (Cell& c : cells[ri]) {
      const ImageMetrics m = compareImages(c.image, cells[ri][ref].image);
      const bool self = &c == &cells[ri][ref];
      table.push_back({row.label, c.caption, c.pipeline, fmt(c.ms, 1),
                       self ? "(reference)" : fmt(m.psnr, 1), self ? "" : fmt(m.ssim, 4)});
      files.stage((fs::path(o.out) / c.file).string(), encodePng(c.file, c.image));
      report.image(c.file, row.label + ": " + c.caption + " (" + c.pipeline + ", " + fmt(c.ms, 1) +
                               " ms per frame)");
    }
  }
  const Buffer sheet = contactSheet(cells, o.rows, o.width, o.height);
  files.stage((fs::path(o.out) / "contact_sheet.png").string(), encodePng("contact_sheet", sheet));
  files.commit();
  report.image("contact_sheet.png", "All rows, labelled with pipeline and median ms per frame");
  report.markdown(
      "Each image: " + std::to_string(o.frames) + " frames of a still camera at " +
      std::to_string(o.width) + "x" + std::to_string(o.height) +
      " (temporal passes converge); the time is the median frame after the first (which builds "
      "the BVH and probes). PSNR and SSIM compare each image with its row's fully ray-traced "
      "one: the same shading traced everywhere, so the difference is what the cheaper pipeline "
      "leaves out.\n\n");
  report.table("demo", {"row", "image", "pipeline", "ms / frame", "PSNR dB vs ray traced", "SSIM"},
               table);
  report.write("width " + std::to_string(o.width) + ", height " + std::to_string(o.height) +
               ", frames " + std::to_string(o.frames));
  std::printf("demo: wrote %s and %s\n", (fs::path(o.out) / "contact_sheet.png").c_str(),
              (fs::path(o.out) / "index.html").c_str());
  return 0;
}

}  // namespace tandem
