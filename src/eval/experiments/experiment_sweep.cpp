#include "eval/experiments/experiment_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/image_io.h"
#include "core/json_fields.h"
#include "eval/experiments/experiment_report.h"
#include "eval/metrics/flip.h"
#include "eval/metrics/metrics.h"
#include "eval/reference/reference_cache.h"
#include "pipeline/aov.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace fs = std::filesystem;

namespace {

struct SweepSpec {
  std::string title, description;
  std::vector<std::string> scenes, pipelines, set;
  int width = 320, height = 180, warmup = 1, frames = 3;
  std::string param;  // "label.param"; empty: no sweep
  std::vector<double> values;
  bool logX = false;
  ReferenceSettings reference;
  uint64_t seed = 1;  // renders differ in seed from the reference, so noise is not shared
  std::vector<std::string> plotMetrics{"ssim", "flip", "ms"};
  bool logMetrics = false;
};

std::vector<std::string> stringList(JsonFields& f, const std::string& key, bool required) {
  std::vector<std::string> out;
  if (!f.has(key)) {
    if (required) f.fail(key, "is required");
    return out;
  }
  const Json& a = f.raw(key);
  if (!a.is_array()) f.fail(key, "expected an array of strings");
  for (size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_string()) f.fail(key + "[" + std::to_string(i) + "]", "expected a string");
    out.push_back(a[i].get<std::string>());
  }
  return out;
}

SweepSpec parse(const Json& j, const std::string& file) {
  SweepSpec s;
  JsonFields f(j, file, "");
  f.string("runner", "sweep");
  s.title = f.string("title", fs::path(file).stem().string());
  s.description = f.string("description", "");
  s.scenes = stringList(f, "scenes", true);
  s.pipelines = stringList(f, "pipelines", true);
  s.set = stringList(f, "set", false);
  if (s.scenes.empty()) f.fail("scenes", "must name at least one scene");
  if (s.pipelines.empty()) f.fail("pipelines", "must name at least one pipeline");
  s.width = f.integer("width", s.width, 8, 16384);
  s.height = f.integer("height", s.height, 8, 16384);
  s.warmup = f.integer("warmup", s.warmup, 0, 1000);
  s.frames = f.integer("frames", s.frames, 1, 10000);
  s.seed = uint64_t(f.integer("seed", int(s.seed), 0, 1 << 30));
  // Scene files are named relative to the experiment file.
  const fs::path base = fs::path(file).parent_path();
  for (std::string& sc : s.scenes)
    if (sc.find('.') != std::string::npos && fs::path(sc).is_relative()) sc = (base / sc).string();
  if (f.has("sweep")) {
    JsonFields w(f.raw("sweep"), file, "sweep");
    s.param = w.string("param", "");
    if (s.param.find('.') == std::string::npos) w.fail("param", "expected pass.param");
    if (!w.has("values") || !w.raw("values").is_array() || w.raw("values").empty())
      w.fail("values", "expected a non-empty array of numbers");
    for (const Json& v : w.raw("values")) {
      if (!v.is_number()) w.fail("values", "expected numbers");
      s.values.push_back(v.get<double>());
    }
    s.logX = w.boolean("logX", false);
    w.finish();
  }
  if (f.has("reference")) {
    JsonFields r(f.raw("reference"), file, "reference");
    s.reference.spp = r.integer("spp", 256, 1, 1 << 20);
    const std::string integrator = r.string("integrator", "path");
    if (integrator != "path" && integrator != "whitted" && integrator != "diffuse-gi")
      r.fail("integrator", "expected path, whitted or diffuse-gi");
    s.reference.integrator = integrator == "whitted"      ? Integrator::Whitted
                             : integrator == "diffuse-gi" ? Integrator::DiffuseGI
                                                          : Integrator::Path;
    s.reference.path.maxDepth = r.integer("maxDepth", 16, 1, 1024);
    s.reference.whitted.maxDepth = r.integer("whittedDepth", 10, 1, 64);
    s.reference.seed = uint64_t(r.integer("seed", 0, 0, 1 << 30));
    r.finish();
  } else {
    s.reference.spp = 256;
  }
  if (f.has("plots")) {
    JsonFields p(f.raw("plots"), file, "plots");
    s.plotMetrics = stringList(p, "metrics", true);
    for (const std::string& m : s.plotMetrics)
      if (m != "ssim" && m != "flip" && m != "rmse" && m != "psnr" && m != "ms")
        p.fail("metrics", "'" + m + "' is not one of ssim, flip, rmse, psnr, ms");
    s.logMetrics = p.boolean("logY", false);
    p.finish();
  }
  f.finish();
  return s;
}

bool hasPass(const Pipeline& p, const std::string& assignment) {
  const std::string label = assignment.substr(0, assignment.find('.'));
  for (const auto& pass : p.passes)
    if (pass->label == label) return true;
  return false;
}

std::string valueText(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

struct Row {
  std::string scene, pipeline;
  double value = std::numeric_limits<double>::quiet_NaN();
  double ms = 0, rmse = 0, psnr = 0, ssim = 0, flip = 0;
  double metric(const std::string& m) const {
    return m == "ssim" ? ssim : m == "flip" ? flip : m == "rmse" ? rmse : m == "psnr" ? psnr : ms;
  }
};

// Every `set` and the sweep's parameter must name a pass of some pipeline.
void checkParams(const SweepSpec& s, const std::string& file) {
  bool sweepApplies = false;
  std::vector<bool> setApplies(s.set.size(), false);
  for (const std::string& name : s.pipelines) {
    Pipeline p = Pipeline::load(name);
    for (size_t i = 0; i < s.set.size(); ++i)
      if (hasPass(p, s.set[i])) p.setParam(s.set[i], file + ": set"), setApplies[i] = true;
    if (!s.param.empty() && hasPass(p, s.param)) {
      sweepApplies = true;
      for (double v : s.values) p.setParam(s.param + "=" + valueText(v), file + ": sweep");
    }
  }
  auto passLabel = [](const std::string& a) { return a.substr(0, a.find('.')); };
  if (!s.param.empty() && !sweepApplies)
    throw InputError(file, "sweep.param",
                     "no pipeline has a pass labelled '" + passLabel(s.param) + "'");
  for (size_t i = 0; i < s.set.size(); ++i)
    if (!setApplies[i])
      throw InputError(file, "set[" + std::to_string(i) + "]",
                       "no pipeline has a pass labelled '" + passLabel(s.set[i]) + "'");
}

// One render of the sweep: pipeline `name` (at value v of the swept parameter), timed and
// compared with the reference.
Row renderPoint(const SweepSpec& s, const std::string& file, const Scene& scene,
                const CameraDesc& cam, const std::string& label, const std::string& name,
                bool swept, double v, const Buffer& refDisplay, ExperimentReport& report) {
  Pipeline p = Pipeline::load(name);
  for (const std::string& a : s.set)
    if (hasPass(p, a)) p.setParam(a, file + ": set");
  if (swept) p.setParam(s.param + "=" + valueText(v), file + ": sweep");
  Renderer r(scene, std::move(p),
             RenderSettings{.width = s.width, .height = s.height, .seed = s.seed});
  r.keepOnDevice();  // timed: nothing read back until the frames are done
  for (int i = 0; i < s.warmup; ++i) r.renderFrame(0, cam);
  std::vector<double> ms;
  for (int i = 0; i < s.frames; ++i) ms.push_back(r.renderFrame(0, cam).totalMs);
  Row row;
  row.scene = label;
  row.pipeline = name;
  row.value = v;
  row.ms = summarize(ms).median;
  const ImageMetrics m = compareImages(refDisplay, r.output());
  Buffer flipMap;
  row.rmse = m.rmse, row.psnr = m.psnr, row.ssim = m.ssim;
  row.flip = flip(refDisplay, r.output(), &flipMap);
  const std::string tag = label + "_" + name + (swept ? "_" + valueText(v) : "");
  writePng((report.dir() / (tag + ".png")).string(), r.output());
  writePng((report.dir() / (tag + "_flip.png")).string(), flipColorMap(flipMap));
  report.image(tag + ".png", tag + ": " + fmt(row.ms, 1) + " ms, SSIM " + fmt(row.ssim, 4) +
                                 ", FLIP " + fmt(row.flip, 4));
  report.image(tag + "_flip.png", tag + ": FLIP error map");
  std::printf("  %-28s %9.1f ms  ssim %.4f  flip %.4f\n",
              (name + (swept ? " " + s.param + "=" + valueText(v) : "")).c_str(), row.ms, row.ssim,
              row.flip);
  std::fflush(stdout);
  return row;
}

// Per scene and metric, the metric against the swept value (unswept pipelines: flat lines).
void sweepPlots(const SweepSpec& s, const std::vector<Row>& rows, ExperimentReport& report) {
  if (!s.param.empty()) {
    const double lo = *std::min_element(s.values.begin(), s.values.end());
    const double hi = *std::max_element(s.values.begin(), s.values.end());
    for (size_t si = 0; si < s.scenes.size(); ++si) {
      const std::string label = sceneLabel(s.scenes[si]);
      for (const std::string& m : s.plotMetrics) {
        std::vector<PlotSeries> series;
        for (const std::string& name : s.pipelines) {
          PlotSeries ps{name, {}, {}};
          for (const Row& r : rows)
            if (r.scene == label && r.pipeline == name) {
              // An unswept pipeline is a baseline: a flat line over the swept range.
              ps.x.push_back(std::isnan(r.value) ? lo : r.value);
              ps.y.push_back(r.metric(m));
              if (std::isnan(r.value)) ps.x.push_back(hi), ps.y.push_back(r.metric(m));
            }
          series.push_back(ps);
        }
        report.plot(label + "_" + m, label + ": " + m + " against " + s.param, s.param,
                    m == "ms" ? "frame time (ms)" : m, series, s.logX, s.logMetrics && m != "ssim");
      }
    }
  }
}

}  // namespace

int runSweepExperiment(const Json& j, const std::string& file, const ExperimentOverrides& o) {
  SweepSpec s = parse(j, file);
  if (!o.scenes.empty()) s.scenes = o.scenes;
  if (o.width) s.width = o.width;
  if (o.height) s.height = o.height;
  if (o.warmup >= 0) s.warmup = o.warmup;
  if (o.frames) s.frames = o.frames;
  if (o.spp) s.reference.spp = o.spp;
  s.reference.progress = true;
  // Check every scene and pipeline (and the sweep's parameter) before rendering anything.
  std::vector<Scene> scenes;
  for (const std::string& spec : s.scenes) {
    scenes.push_back(loadScene(spec));
  }
  checkParams(s, file);
  const std::string stem = fs::path(file).stem().string();
  ExperimentReport report(o.out.empty() ? "out/experiment-" + stem : o.out, s.title);
  if (!s.description.empty()) report.markdown(s.description + "\n\n");
  const std::string cache = o.noCache ? "" : o.cache;

  std::vector<Row> rows;
  for (size_t si = 0; si < scenes.size(); ++si) {
    const Scene& scene = scenes[si];
    const std::string label = sceneLabel(s.scenes[si]);
    const CameraDesc cam = defaultCamera(scene);
    ReferenceJob job;
    job.scene = &scene;
    job.camera = job.shutterCamera = cam;
    job.width = s.width;
    job.height = s.height;
    job.settings = s.reference;
    std::printf("experiment %s: %s reference (%d spp)\n", stem.c_str(), label.c_str(),
                s.reference.spp);
    std::fflush(stdout);
    const ReferenceImage ref = referenceImage(job, cache);
    const Buffer refDisplay = visualizeBuffer(ref.hdr);
    writePng((report.dir() / (label + "_reference.png")).string(), refDisplay);
    report.image(label + "_reference.png", label + ": reference, " + std::to_string(ref.spp) +
                                               " spp" + (ref.fromCache ? " (cached)" : ""));
    for (const std::string& name : s.pipelines) {
      const bool swept = !s.param.empty() && hasPass(Pipeline::load(name), s.param);
      std::vector<double> values = swept ? s.values : std::vector<double>{std::nan("")};
      for (double v : values) {
        rows.push_back(renderPoint(s, file, scene, cam, label, name, swept, v, refDisplay, report));
      }
    }
  }

  std::vector<std::vector<std::string>> table;
  for (const Row& r : rows)
    table.push_back({r.scene, r.pipeline, std::isnan(r.value) ? "" : valueText(r.value),
                     fmt(r.ms, 2), fmt(r.rmse, 5), fmt(r.psnr, 2), fmt(r.ssim, 4), fmt(r.flip, 4)});
  report.table("results",
               {"scene", "pipeline", s.param.empty() ? "value" : s.param, "frame_ms", "rmse",
                "psnr_db", "ssim", "flip"},
               table);
  if (!s.param.empty()) sweepPlots(s, rows, report);
  report.write(std::to_string(s.width) + "x" + std::to_string(s.height) + "; reference " +
               std::to_string(s.reference.spp) + " spp (seed " + std::to_string(s.reference.seed) +
               "), renders seed " + std::to_string(s.seed) + "; frame time = median of " +
               std::to_string(s.frames) + " frames after " + std::to_string(s.warmup) +
               " warm-up; metrics on display-encoded (ACES, sRGB) "
               "images against the reference. Experiment file: " +
               file + ".");
  return 0;
}

}  // namespace tandem
