#include "eval/experiments/experiment_heuristic.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <thread>
#include <utility>

#include "core/error.h"
#include "core/image_io.h"
#include "core/json_fields.h"
#include "eval/experiments/experiment_report.h"
#include "eval/metrics/metrics.h"
#include "passes/common/deferred_shading.h"
#include "passes/heuristic/heuristic.h"
#include "passes/heuristic/rt_secondary.h"
#include "passes/heuristic/ss_fallback.h"
#include "pipeline/pass_edit.h"
#include "pipeline/pass_times.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

#ifndef TANDEM_SOURCE_DIR
#define TANDEM_SOURCE_DIR "."
#endif

namespace tandem {
namespace fs = std::filesystem;

std::vector<std::string> defaultHeuristicScenes() {
  const std::string dir = std::string(TANDEM_SOURCE_DIR) + "/scenes/";
  return {"spheres", dir + "atrium_spheres.json", dir + "atrium_statue.json",
          dir + "cornell_spheres.json"};
}

HeuristicExperimentOptions heuristicOptionsFromJson(const nlohmann::json& j,
                                                    const std::string& file) {
  HeuristicExperimentOptions o;
  JsonFields f(j, file, "");
  f.string("runner", "heuristic");
  f.string("title", "");
  f.string("description", "");
  if (f.has("scenes")) {
    const Json& a = f.raw("scenes");
    if (!a.is_array()) f.fail("scenes", "expected an array of scene names or files");
    const fs::path base = fs::path(file).parent_path();
    for (size_t i = 0; i < a.size(); ++i) {
      if (!a[i].is_string()) f.fail("scenes[" + std::to_string(i) + "]", "expected a string");
      std::string sc = a[i].get<std::string>();
      // Files are named relative to the experiment file; built-in names have no dot.
      if (sc.find('.') != std::string::npos && fs::path(sc).is_relative())
        sc = (base / sc).string();
      o.scenes.push_back(sc);
    }
  }
  o.width = f.integer("width", o.width, 8, 16384);
  o.height = f.integer("height", o.height, 8, 16384);
  o.warmup = f.integer("warmup", o.warmup, 0, 1000);
  o.staticFrames = f.integer("staticFrames", o.staticFrames, 1, 10000);
  o.pathFrames = f.integer("pathFrames", o.pathFrames, 1, 100000);
  o.budget = f.number("budget", float(o.budget), 0.0f, 1e30f);
  o.budgetMs = f.number("budgetMs", float(o.budgetMs), 1e-3f, 1e9f);
  o.tolerance = f.number("tolerance", float(o.tolerance), 0.0f, 10.0f);
  f.finish();
  return o;
}

namespace {

// One pipeline rendering one scene; its heuristic (if any) reports through frame counters.
struct Run {
  std::string pipeline;
  std::unique_ptr<Renderer> renderer;
  bool heuristic = false;
  // A counter the pipeline declares (checked when the run loads); 0 on a frame that did not
  // report it (rt_secondary cuts items only under a deadline).
  double counter(const char* name) const { return renderer->context().counter(name, 0.0); }

  Run(const Scene& scene, const std::string& name, const PipelineEdits& edits,
      const HeuristicExperimentOptions& o)
      : pipeline(name) {
    Pipeline p = Pipeline::load(name);
    applyEdits(p, edits);
    RenderSettings settings{.width = o.width, .height = o.height};
    renderer = std::make_unique<Renderer>(scene, std::move(p), settings);
    renderer->keepOnDevice();  // timed: images and masks read back after the frames
    for (const auto& pass : renderer->pipeline().passes) heuristic |= pass->type() == "heuristic";
    if (heuristic)
      for (const char* c : {HeuristicCounters::selected, HeuristicCounters::nodes,
                            HeuristicCounters::visibleObjects, RTSecondaryCounters::itemsCut})
        renderer->pipeline().requireCounter(c, "experiment heuristic");
  }
};

// Median per pass and of the frame over the timed frames of a static shot.
struct StaticResult {
  std::map<std::string, double> ms;  // pass type -> median (found through the pipeline)
  double frame = 0;
  size_t selected = 0, visible = 0;
  Buffer image, mask;
};

StaticResult runStatic(Run& run, const CameraDesc& cam, const HeuristicExperimentOptions& o) {
  for (int i = 0; i < o.warmup; ++i) run.renderer->renderFrame(0, cam);
  std::map<std::string, std::vector<double>> samples;
  std::vector<double> frames;
  for (int i = 0; i < o.staticFrames; ++i) {
    FrameTimings ft = run.renderer->renderFrame(0, cam);  // frame 0 every time: a static shot
    for (const PassTiming& p : ft.passes) samples[p.name].push_back(p.ms);
    frames.push_back(ft.totalMs);
  }
  StaticResult r;
  std::map<std::string, double> medians;
  for (auto& [name, v] : samples) medians[name] = summarize(v).median;
  r.ms = PassTimes(run.renderer->pipeline(), std::move(medians)).byType();
  r.frame = summarize(frames).median;
  r.image = run.renderer->output();
  if (run.heuristic) {
    r.selected = size_t(run.counter(HeuristicCounters::selected));
    r.visible = size_t(run.counter(HeuristicCounters::visibleObjects));
    // What was ray traced: the mask less the tiles a deadline cut.
    const FrameContext& ctx = run.renderer->context();
    r.mask = run.renderer->fetch(ctx.has("traced_mask") ? "traced_mask" : "heuristic_mask");
  }
  return r;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / double(v.size());
}

struct SceneResult {
  std::string name;
  StaticResult heur, all, budget, rtOnly, product;
  ImageMetrics heurVsAll, budgetVsAll, allVsRtOnly, productVsRtOnly, heurVsRtOnly;
  // Path (Table 6).
  int pathFrames = 0;
  double pathHeurMs = 0, pathAllMs = 0, pathBudgetMs = 0, pathHeurSsim = 0, pathBudgetSsim = 0;
  int withinBand = 0, binding = 0, bindingWithin = 0;
  std::vector<double> budgetRtMs;
};

void validate(const HeuristicExperimentOptions& o) {
  const char* cl = "command line";
  if (o.width < 8 || o.width > 16384) throw InputError(cl, "--width", "must be in [8, 16384]");
  if (o.height < 8 || o.height > 16384) throw InputError(cl, "--height", "must be in [8, 16384]");
  if (o.warmup < 0 || o.warmup > 1000) throw InputError(cl, "--warmup", "must be in [0, 1000]");
  if (o.staticFrames < 1 || o.staticFrames > 10000)
    throw InputError(cl, "--static-frames", "must be in [1, 10000]");
  if (o.pathFrames < 1 || o.pathFrames > 100000)
    throw InputError(cl, "--path-frames", "must be in [1, 100000]");
  if (!(o.budget >= 0)) throw InputError(cl, "--budget", "must be >= 0");
  if (!(o.budgetMs > 0)) throw InputError(cl, "--budget-ms", "must be > 0");
}

// The settings of the runs: T, the ms budget, and the paper's rules for its tables.
struct RunSettings {
  PipelineEdit T, budgetMs;
  // Unselected effects are absent (no fallbacks).
  PipelineEdit noFallback = editPass<ScreenSpaceFallbackPass>(
      [](FallbackSettings& f) { f.mode = FallbackSettings::Mode::Off; });
  // No shadow maps: neither deferred shading's nor the fallback's.
  PipelineEdit noShadowMaps = [](Pipeline& p) {
    editPass<DeferredShadingPass>(
        [](DeferredSettings& d) { d.shadows = DeferredSettings::Shadows::Off; })(p);
    editPass<ScreenSpaceFallbackPass>(
        [](FallbackSettings& f) { f.shadows = FallbackSettings::Shadows::Off; })(p);
  };
  // Shadows selected with their object (the pipeline traces them all).
  PipelineEdit paperShadows = editPass<HeuristicPass>(
      [](HeuristicSettings& h) { h.shadows = HeuristicSettings::Shadows::Budget; });
};

// Table 5: the static shot, each pipeline, and the images compared.
void staticShot(const Scene& scene, const CameraDesc& cam, const HeuristicExperimentOptions& o,
                const RunSettings& rs, const fs::path& dir, SceneResult& res) {
  const PipelineEdit &T = rs.T, &budgetMs = rs.budgetMs, &noFallback = rs.noFallback,
                     &noShadowMaps = rs.noShadowMaps, &paperShadows = rs.paperShadows;
  // Table 5: the static shot.
  {
    Run heur(scene, "hybrid-heuristic", {T, noFallback, noShadowMaps, paperShadows}, o),
        all(scene, "hybrid-all", {}, o),
        budget(scene, "hybrid-budget", {budgetMs, noFallback, noShadowMaps}, o),
        rt(scene, "rt-only", {}, o), product(scene, "hybrid-heuristic", {}, o);
    res.heur = runStatic(heur, cam, o);
    res.all = runStatic(all, cam, o);
    res.budget = runStatic(budget, cam, o);
    res.rtOnly = runStatic(rt, cam, o);
    res.product = runStatic(product, cam, o);
  }
  res.heurVsRtOnly = compareImages(res.heur.image, res.rtOnly.image);
  res.productVsRtOnly = compareImages(res.product.image, res.rtOnly.image);
  res.heurVsAll = compareImages(res.heur.image, res.all.image);
  res.budgetVsAll = compareImages(res.budget.image, res.all.image);
  res.allVsRtOnly = compareImages(res.all.image, res.rtOnly.image);
  const std::string stem = (dir / res.name).string();
  writePng(stem + "_hybrid-heuristic.png", res.heur.image);
  writePng(stem + "_hybrid-all.png", res.all.image);
  writePng(stem + "_hybrid-budget.png", res.budget.image);
  writePng(stem + "_rt-only.png", res.rtOnly.image);
  writePng(stem + "_hybrid-heuristic-fallbacks.png", res.product.image);
  writePng(stem + "_heuristic_mask.png", res.heur.mask);
  writePng(stem + "_budget_mask.png", res.budget.mask);
}

// Table 6 and budget tracking: the camera path, the three hybrids frame by frame.
void cameraPath(const Scene& scene, const CameraDesc& cam, const HeuristicExperimentOptions& o,
                const RunSettings& rs, SceneResult& res) {
  const PipelineEdit &T = rs.T, &budgetMs = rs.budgetMs, &noFallback = rs.noFallback,
                     &noShadowMaps = rs.noShadowMaps, &paperShadows = rs.paperShadows;
  Run heur(scene, "hybrid-heuristic", {T, noFallback, noShadowMaps, paperShadows}, o),
      all(scene, "hybrid-all", {}, o),
      budget(scene, "hybrid-budget", {budgetMs, noFallback, noShadowMaps}, o);
  const int n = o.pathFrames;
  for (int i = 0; i < o.warmup; ++i)
    for (Run* r : {&heur, &all, &budget}) r->renderer->renderFrame(0, pathCamera(scene, cam, 0, n));
  std::vector<double> heurMs, allMs, budgetFrameMs, heurSsim, budgetSsim;
  for (int f = 0; f < n; ++f) {
    CameraDesc c = pathCamera(scene, cam, f, n);
    heurMs.push_back(heur.renderer->renderFrame(f, c).totalMs);
    allMs.push_back(all.renderer->renderFrame(f, c).totalMs);
    FrameTimings bt = budget.renderer->renderFrame(f, c);
    budgetFrameMs.push_back(bt.totalMs);
    double rtMs = PassTimes(budget.renderer->pipeline(), bt).ofType("rt_secondary");
    res.budgetRtMs.push_back(rtMs);
    bool within = std::abs(rtMs - o.budgetMs) <= o.tolerance * o.budgetMs;
    // The budget binds when something visible was left out (not selected, or cut by the
    // deadline); otherwise the RT stage simply had less to do than the budget allows.
    bool binds =
        budget.counter(HeuristicCounters::selected) < budget.counter(HeuristicCounters::nodes) ||
        budget.counter(RTSecondaryCounters::itemsCut) > 0;
    res.withinBand += within;
    res.binding += binds;
    res.bindingWithin += binds && within;
    // Image quality along the path against hybrid-all (every frame up to 50, then sparser).
    if (f < 50 || f % 5 == 0) {
      heurSsim.push_back(ssim(heur.renderer->output(), all.renderer->output()));
      budgetSsim.push_back(ssim(budget.renderer->output(), all.renderer->output()));
    }
  }
  res.pathFrames = n;
  res.pathHeurMs = mean(heurMs);
  res.pathAllMs = mean(allMs);
  res.pathBudgetMs = mean(budgetFrameMs);
  res.pathHeurSsim = mean(heurSsim);
  res.pathBudgetSsim = mean(budgetSsim);
}

void writeCsvs(const std::vector<SceneResult>& results, const HeuristicExperimentOptions& o,
               const fs::path& dir) {
  std::ostringstream t5, t6, bf;
  t5 << "scene,rast_ms,heur_ms,rayt_ms,frame_ms,rt_only_frame_ms,ratio,heur_share,selected,"
        "visible,ssim_vs_all,psnr_vs_all,hybrid_all_frame_ms,ssim_all_vs_rt_only,"
        "budget_frame_ms,budget_rayt_ms,budget_ssim_vs_all,ssim_vs_rt_only,"
        "fallbacks_frame_ms,fallbacks_ratio,fallbacks_ssim_vs_rt_only\n";
  t6 << "scene,frames,with_heuristic_ms,no_heuristic_ms,budget_ms_mode_ms,ssim_heuristic_vs_all,"
        "ssim_budget_vs_all,budget_ms,within_band,binding_frames,binding_within_band\n";
  bf << "scene,frame,rt_ms,budget_ms\n";
  for (const SceneResult& r : results) {
    const StaticResult& h = r.heur;
    double rast = h.ms.at("raster_gbuffer") + h.ms.at("deferred_shading");
    t5 << r.name << "," << rast << "," << h.ms.at("heuristic") << "," << h.ms.at("rt_secondary")
       << "," << h.frame << "," << r.rtOnly.frame << "," << h.frame / r.rtOnly.frame << ","
       << h.ms.at("heuristic") / h.frame << "," << h.selected << "," << h.visible << ","
       << r.heurVsAll.ssim << "," << r.heurVsAll.psnr << "," << r.all.frame << ","
       << r.allVsRtOnly.ssim << "," << r.budget.frame << "," << r.budget.ms.at("rt_secondary")
       << "," << r.budgetVsAll.ssim << "," << r.heurVsRtOnly.ssim << "," << r.product.frame << ","
       << r.product.frame / r.rtOnly.frame << "," << r.productVsRtOnly.ssim << "\n";
    t6 << r.name << "," << r.pathFrames << "," << r.pathHeurMs << "," << r.pathAllMs << ","
       << r.pathBudgetMs << "," << r.pathHeurSsim << "," << r.pathBudgetSsim << "," << o.budgetMs
       << "," << r.withinBand << "," << r.binding << "," << r.bindingWithin << "\n";
    for (size_t f = 0; f < r.budgetRtMs.size(); ++f)
      bf << r.name << "," << f << "," << r.budgetRtMs[f] << "," << o.budgetMs << "\n";
  }
  writeTextFile((dir / "table5.csv").string(), t5.str());
  writeTextFile((dir / "table6.csv").string(), t6.str());
  writeTextFile((dir / "budget_frames.csv").string(), bf.str());
}

// The paper's table layout (rows = measures, columns = scenes).
class MeasureTable {
 public:
  MeasureTable(std::ostringstream& md, const std::vector<SceneResult>& results)
      : md_(md), results_(results) {}
  void header(const char* first) {
    md_ << "| " << first << " |";
    for (const SceneResult& r : results_) md_ << " " << r.name << " |";
    md_ << "\n| --- |";
    for (size_t i = 0; i < results_.size(); ++i) md_ << " ---: |";
    md_ << "\n";
  }
  template <class Value>
  void row(const std::string& label, Value value) {
    md_ << "| " << label << " |";
    for (const SceneResult& r : results_) md_ << " " << value(r) << " |";
    md_ << "\n";
  }

 private:
  std::ostringstream& md_;
  const std::vector<SceneResult>& results_;
};

// Table 5 (the static shot) and the fallbacks beside it.
void table5(std::ostringstream& md, const std::vector<SceneResult>& results) {
  MeasureTable m(md, results);
  md << "## Table 5: static shot (ms, medians)\n\n";
  m.header("measure");
  m.row("FRAME (hybrid-heuristic)", [](const SceneResult& r) { return fmt(r.heur.frame); });
  m.row("RAST (raster_gbuffer + deferred_shading)", [](const SceneResult& r) {
    return fmt(r.heur.ms.at("raster_gbuffer") + r.heur.ms.at("deferred_shading"));
  });
  m.row("HEUR", [](const SceneResult& r) { return fmt(r.heur.ms.at("heuristic")); });
  m.row("RAYT (rt_secondary)",
        [](const SceneResult& r) { return fmt(r.heur.ms.at("rt_secondary")); });
  m.row("RAYT ONLY FRAME (rt-only)", [](const SceneResult& r) { return fmt(r.rtOnly.frame); });
  m.row("FRAME / RAYT ONLY FRAME",
        [](const SceneResult& r) { return fmt(r.heur.frame / r.rtOnly.frame, 3); });
  m.row("HEUR share of FRAME", [](const SceneResult& r) {
    return fmt(100.0 * r.heur.ms.at("heuristic") / r.heur.frame, 2) + " %";
  });
  m.row("objects selected / visible", [](const SceneResult& r) {
    return std::to_string(r.heur.selected) + " / " + std::to_string(r.heur.visible);
  });
  m.row("SSIM vs hybrid-all", [](const SceneResult& r) { return fmt(r.heurVsAll.ssim, 4); });
  m.row("PSNR vs hybrid-all (dB)", [](const SceneResult& r) { return fmt(r.heurVsAll.psnr, 1); });
  m.row("FRAME (hybrid-all)", [](const SceneResult& r) { return fmt(r.all.frame); });
  m.row("SSIM hybrid-all vs rt-only",
        [](const SceneResult& r) { return fmt(r.allVsRtOnly.ssim, 4); });
  m.row("FRAME (hybrid-budget)", [](const SceneResult& r) { return fmt(r.budget.frame); });
  m.row("RAYT (hybrid-budget)",
        [](const SceneResult& r) { return fmt(r.budget.ms.at("rt_secondary")); });
  m.row("SSIM hybrid-budget vs hybrid-all",
        [](const SceneResult& r) { return fmt(r.budgetVsAll.ssim, 4); });
  md << "\n## Beyond the paper: fallbacks for unselected effects (product default)\n\n"
        "The rows above follow the paper's rule (`ss_fallback.mode=off`, `shadows=off`): what the "
        "heuristic leaves out is drawn without shadows and mirrors black. The product "
        "`hybrid-heuristic`, run with its own settings, fills those pixels from raster shadow maps "
        "and per-object reflection probes (`ss_fallback`); it traces no shadow (every pixel's "
        "from the maps, sized to the frame) and spends its own T on reflections and refractions "
        "alone (`heuristic.shadows=maps`).\n\n";
  m.header("measure");
  m.row("SSIM paper's rule vs rt-only",
        [](const SceneResult& r) { return fmt(r.heurVsRtOnly.ssim, 4); });
  m.row("SSIM with fallbacks vs rt-only",
        [](const SceneResult& r) { return fmt(r.productVsRtOnly.ssim, 4); });
  m.row("FRAME with fallbacks", [](const SceneResult& r) { return fmt(r.product.frame); });
  m.row("ss_fallback pass",
        [](const SceneResult& r) { return fmt(r.product.ms.at("ss_fallback")); });
  m.row("FRAME with fallbacks / RAYT ONLY FRAME",
        [](const SceneResult& r) { return fmt(r.product.frame / r.rtOnly.frame, 3); });
}

// Table 6 (the camera path) and the ms budget's tracking.
void table6(std::ostringstream& md, const std::vector<SceneResult>& results,
            const HeuristicExperimentOptions& o) {
  MeasureTable m(md, results);
  md << "\n## Table 6: mean frame time along the camera path (ms)\n\n";
  m.header("measure");
  m.row("with heuristic (hybrid-heuristic)",
        [](const SceneResult& r) { return fmt(r.pathHeurMs); });
  m.row("no heuristic (hybrid-all)", [](const SceneResult& r) { return fmt(r.pathAllMs); });
  m.row("ms budget (hybrid-budget)", [](const SceneResult& r) { return fmt(r.pathBudgetMs); });
  m.row("mean SSIM hybrid-heuristic vs hybrid-all",
        [](const SceneResult& r) { return fmt(r.pathHeurSsim, 4); });
  m.row("mean SSIM hybrid-budget vs hybrid-all",
        [](const SceneResult& r) { return fmt(r.pathBudgetSsim, 4); });
  md << "\n## ms budget tracking along the path (RT stage vs " << fmt(o.budgetMs, 1)
     << " ms, band ±" << fmt(o.tolerance * 100, 0) << " %)\n\n";
  m.header("measure");
  m.row("frames within the band", [](const SceneResult& r) {
    return fmt(100.0 * r.withinBand / std::max(r.pathFrames, 1), 1) + " %";
  });
  m.row("frames where the budget binds", [](const SceneResult& r) {
    return std::to_string(r.binding) + " / " + std::to_string(r.pathFrames);
  });
  m.row("binding frames within the band", [](const SceneResult& r) {
    return r.binding ? fmt(100.0 * r.bindingWithin / r.binding, 1) + " %" : std::string("-");
  });
  m.row("RT stage median (ms)",
        [](const SceneResult& r) { return fmt(summarize(r.budgetRtMs).median); });
}

// The budget tracking, frame by frame: the RT stage's time against the budget.
void budgetTrackingPlot(ExperimentReport& report, const std::vector<SceneResult>& results,
                        const HeuristicExperimentOptions& o) {
  std::vector<PlotSeries> tracking;
  for (const SceneResult& r : results) {
    PlotSeries ps{r.name, {}, r.budgetRtMs};
    for (size_t f = 0; f < r.budgetRtMs.size(); ++f) ps.x.push_back(double(f));
    tracking.push_back(ps);
  }
  tracking.push_back(
      {"budget", {0.0, double(std::max(o.pathFrames - 1, 1))}, {o.budgetMs, o.budgetMs}});
  report.plot("budget_tracking", "hybrid-budget: RT stage time along the camera path", "path frame",
              "rt_secondary (ms)", tracking);
}

}  // namespace

int runHeuristicExperiment(const HeuristicExperimentOptions& o) {
  validate(o);
  std::vector<std::string> specs = o.scenes.empty() ? defaultHeuristicScenes() : o.scenes;
  // Load every scene before rendering anything, so a bad one fails fast and writes nothing.
  std::vector<Scene> scenes;
  for (const std::string& spec : specs) {
    scenes.push_back(loadScene(spec));
  }
  if (!o.out.empty() && !fs::exists(o.out)) fs::create_directories(o.out);
  const fs::path dir(o.out);
  const RunSettings rs{
      editPass<HeuristicPass>([&](HeuristicSettings& h) { h.budget = o.budget; }),
      editPass<HeuristicPass>([&](HeuristicSettings& h) { h.budgetMs = o.budgetMs; })};

  std::vector<SceneResult> results;
  for (size_t si = 0; si < scenes.size(); ++si) {
    const Scene& scene = scenes[si];
    SceneResult res;
    res.name = sceneLabel(specs[si]);
    std::printf("experiment heuristic: %s (%zu triangles, %zu objects)\n", res.name.c_str(),
                scene.triangleCount(), scene.objects.size());
    std::fflush(stdout);
    const CameraDesc cam = defaultCamera(scene);

    staticShot(scene, cam, o, rs, dir, res);
    cameraPath(scene, cam, o, rs, res);
    const int n = o.pathFrames;
    std::printf(
        "  static: hybrid-heuristic %.1f ms, rt-only %.1f ms (ratio %.2f), SSIM vs hybrid-all "
        "%.4f\n  with fallbacks: %.1f ms (ratio %.2f), SSIM vs rt-only %.4f (paper's rule %.4f)\n"
        "  path: %d frames, with heuristic %.1f ms, without %.1f ms; budget %.0f ms: "
        "%d/%d frames within ±%.0f%%\n",
        res.heur.frame, res.rtOnly.frame, res.heur.frame / res.rtOnly.frame, res.heurVsAll.ssim,
        res.product.frame, res.product.frame / res.rtOnly.frame, res.productVsRtOnly.ssim,
        res.heurVsRtOnly.ssim, n, res.pathHeurMs, res.pathAllMs, o.budgetMs, res.withinBand, n,
        o.tolerance * 100);
    std::fflush(stdout);
    results.push_back(std::move(res));
  }

  writeCsvs(results, o, dir);

  // The Markdown report: the paper's table layout (rows = measures, columns = scenes).
  ExperimentReport report(dir,
                          "Heuristic hybrid rendering (Walewski et al. 2019): experiment results");
  std::ostringstream md;
  const std::string settings =
      std::to_string(o.width) + "x" + std::to_string(o.height) +
      (o.threads ? ", limited to " + std::to_string(o.threads) + " threads" : std::string()) +
      "; static shots: median of " + std::to_string(o.staticFrames) + " frames after " +
      std::to_string(o.warmup) + " warm-up; path: " + std::to_string(o.pathFrames) +
      " frames. hybrid-heuristic under the paper's rule uses T = " + fmt(o.budget, 0) +
      " cost units (the product run its own settings); hybrid-budget uses " + fmt(o.budgetMs, 1) +
      " ms with per-effect selection and recursion-aware costs.";
  table5(md, results);
  table6(md, results, o);
  md << "\nImages: `<scene>_<pipeline>.png` (static shot), `<scene>_heuristic_mask.png` "
        "(red = shadows, green = reflections, blue = refractions ray traced).\n\n";
  report.markdown(md.str());
  budgetTrackingPlot(report, results, o);
  for (const SceneResult& r : results)
    for (const char* what : {"hybrid-heuristic", "hybrid-all", "hybrid-budget", "rt-only",
                             "heuristic_mask", "budget_mask"})
      report.image(r.name + "_" + what + ".png", r.name + ": " + what);
  report.write(settings);
  return 0;
}

}  // namespace tandem
