// tandem experiment NAME: regenerates an experiment in one command. An experiment is data: a
// JSON file (experiments/NAME.json in the source tree, or any path) whose "runner" picks the
// procedure — "sweep" (scenes x pipelines x a parameter sweep against cached references),
// "heuristic" (seed 002's Tables 5 and 6 and the ms-budget tracking), "taa" (TAA against a
// supersampled render), "hybrid-dof" (seed 000's Table 2 and Figures 6-7), "foveated" (seed 004)
// or "interleaved" (seed 003). Command-line options
// override the file's settings. Every run writes results.md, CSV, PNG plots and index.html.
#include <filesystem>
#include <fstream>
#include <memory>

#include "cli_options.h"
#include "core/error.h"
#include "eval/experiment_dof.h"
#include "eval/experiment_foveated.h"
#include "eval/experiment_gallery.h"
#include "eval/experiment_heuristic.h"
#include "eval/experiment_interleaved.h"
#include "eval/experiment_sweep.h"
#include "eval/experiment_taa.h"
#include "verbs.h"

#ifndef TANDEM_SOURCE_DIR
#define TANDEM_SOURCE_DIR "."
#endif

namespace tandem {
namespace fs = std::filesystem;

namespace {

struct ExperimentVerb {
  std::string name;
  bool list = false;
  ExperimentOverrides o;
  int staticFrames = -1, pathFrames = -1, threads = 0;  // -1: not given
  double budget = -1, budgetMs = -1;

  static fs::path experimentsDir() { return fs::path(TANDEM_SOURCE_DIR) / "experiments"; }

  fs::path resolve() const {
    if (fs::exists(name) && fs::is_regular_file(name)) return name;
    const fs::path p = experimentsDir() / (name + ".json");
    if (fs::exists(p)) return p;
    std::string known;
    if (fs::exists(experimentsDir()))
      for (const auto& e : fs::directory_iterator(experimentsDir()))
        if (e.path().extension() == ".json") known += " " + e.path().stem().string();
    throw InputError(name, "",
                     "not an experiment file and not a built-in experiment (have:" + known + ")");
  }

  int run() {
    if (threads < 0 || threads > 4096)
      throw InputError("command line", "--threads", "must be in [0, 4096]");
    RenderOptions ro;
    ro.threads = threads;
    auto limit = limitThreads(ro);
    if (list || name.empty()) {
      for (const auto& e : fs::directory_iterator(experimentsDir())) {
        if (e.path().extension() != ".json") continue;
        std::ifstream in(e.path());
        const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        std::printf("%-22s %s\n", e.path().stem().string().c_str(),
                    j.is_object() ? j.value("title", "").c_str() : "(unreadable)");
      }
      return name.empty() && !list ? 1 : 0;
    }
    const fs::path file = resolve();
    std::ifstream in(file);
    nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_discarded() || !j.is_object())
      throw InputError(file.string(), "", "not a JSON object");
    const std::string runner = j.value("runner", "sweep");
    if (runner == "heuristic") {
      HeuristicExperimentOptions ho = heuristicOptionsFromJson(j, file.string());
      ho.out = o.out.empty() ? "out/experiment-" + file.stem().string() : o.out;
      if (!o.scenes.empty()) ho.scenes = o.scenes;
      if (o.width) ho.width = o.width;
      if (o.height) ho.height = o.height;
      if (o.warmup >= 0) ho.warmup = o.warmup;
      if (staticFrames != -1) ho.staticFrames = staticFrames;  // range-checked by the runner
      if (pathFrames != -1) ho.pathFrames = pathFrames;
      if (budget >= 0) ho.budget = budget;
      if (budgetMs >= 0) ho.budgetMs = budgetMs;
      ho.threads = threads;
      return runHeuristicExperiment(ho);
    }
    if (runner == "taa") {
      TaaExperimentOptions to = taaOptionsFromJson(j, file.string());
      to.out = o.out.empty() ? "out/experiment-" + file.stem().string() : o.out;
      if (!o.scenes.empty()) to.scenes = o.scenes;
      if (o.width) to.width = o.width;
      if (o.height) to.height = o.height;
      if (o.frames) to.staticFrames = o.frames;
      if (pathFrames != -1) to.pathFrames = pathFrames;
      return runTaaExperiment(to);
    }
    if (runner == "hybrid-dof") {
      DofExperimentOptions d = dofOptionsFromJson(j, file.string());
      d.out = o.out.empty() ? "out/experiment-" + file.stem().string() : o.out;
      d.cache = o.noCache ? "" : o.cache;
      if (o.width) d.width = o.width;
      if (o.height) d.height = o.height;
      if (o.warmup >= 0) d.warmup = o.warmup;
      if (o.frames) d.frames = o.frames;
      if (o.spp) d.referenceSpp = d.pathReferenceSpp = o.spp;
      return runDofExperiment(d);
    }
    if (runner == "foveated") {
      FoveatedExperimentOptions fo = foveatedOptionsFromJson(j, file.string());
      fo.out = o.out.empty() ? "out/experiment-" + file.stem().string() : o.out;
      fo.cache = o.noCache ? "" : o.cache;
      if (o.width) fo.qualityWidth = o.width;
      if (o.height) fo.qualityHeight = o.height;
      if (o.warmup >= 0) fo.warmup = o.warmup;
      if (o.frames) fo.fhdFrames = fo.quest2Frames = o.frames;
      if (o.spp) fo.referenceSpp = o.spp;
      return runFoveatedExperiment(fo);
    }
    if (runner == "interleaved") {
      InterleavedExperimentOptions io = interleavedOptionsFromJson(j, file.string());
      io.out = o.out.empty() ? "out/experiment-" + file.stem().string() : o.out;
      io.cache = o.noCache ? "" : o.cache;
      if (o.width) io.width = o.width;
      if (o.height) io.height = o.height;
      if (o.warmup >= 0) io.timingWarmup = o.warmup;
      if (o.frames) io.timingFrames = o.frames;
      if (o.spp) io.referenceSpp = o.spp;
      if (!o.scenes.empty()) throw InputError("command line", "--scenes", "not for interleaved");
      return runInterleavedExperiment(io);
    }
    if (runner == "gallery") {
      GalleryOptions go = galleryOptionsFromJson(j, file.string());
      go.out = o.out.empty() ? "out/experiment-" + file.stem().string() : o.out;
      if (o.width) go.width = o.width;
      if (o.height) go.height = o.height;
      if (o.frames) {
        go.frames = o.frames;
        for (GalleryRow& r : go.rows) r.frames = 0;  // --frames sets every row's
      }
      if (!o.scenes.empty()) throw InputError("command line", "--scenes", "not for a gallery");
      go.cache = o.noCache ? "" : o.cache;
      if (o.spp)
        for (GalleryRow& r : go.rows) r.groundTruth.spp = o.spp;
      auto limit = threads > 0 ? std::make_unique<tbb::global_control>(
                                     tbb::global_control::max_allowed_parallelism, threads)
                               : nullptr;
      return runGallery(go);
    }
    if (runner != "sweep")
      throw InputError(file.string(), "runner",
                       "'" + runner +
                           "' is not sweep, heuristic, taa, hybrid-dof, foveated, interleaved or "
                           "gallery");
    if (staticFrames != -1 || pathFrames != -1 || budget >= 0 || budgetMs >= 0)
      throw InputError("command line", "--static-frames/--path-frames/--budget/--budget-ms",
                       "apply to the heuristic runner only");
    return runSweepExperiment(j, file.string(), o);
  }
};

}  // namespace

VerbRunner addExperimentVerb(CLI::App& app) {
  auto v = std::make_shared<ExperimentVerb>();
  const char* env = std::getenv("TANDEM_REFERENCE_CACHE");
  v->o.cache = env && *env ? env : "out/reference-cache";
  CLI::App* sub = app.add_subcommand(
      "experiment", "Run an experiment (experiments/NAME.json or a file): tables, plots, index");
  sub->add_option("name", v->name, "Experiment name (see --list) or JSON file");
  sub->add_flag("--list", v->list, "List the built-in experiments");
  sub->add_option("--out", v->o.out, "Output folder (default out/experiment-NAME)");
  sub->add_option("--scenes", v->o.scenes, "Override the scenes (names or files)")->delimiter(',');
  sub->add_option("--width", v->o.width, "Override the image width");
  sub->add_option("--height", v->o.height, "Override the image height");
  sub->add_option("--warmup", v->o.warmup, "Override the untimed frames before measuring");
  sub->add_option("--frames", v->o.frames, "sweep: timed frames per render (median)");
  sub->add_option("--spp", v->o.spp, "sweep: reference samples per pixel");
  sub->add_option("--cache", v->o.cache,
                  "Reference cache folder (default $TANDEM_REFERENCE_CACHE or "
                  "out/reference-cache)");
  sub->add_flag("--no-cache", v->o.noCache, "Render references even when cached");
  sub->add_option("--static-frames", v->staticFrames, "heuristic: timed frames of each shot");
  sub->add_option("--path-frames", v->pathFrames, "heuristic: frames along the camera path");
  sub->add_option("--budget", v->budget, "heuristic: T in cost units for hybrid-heuristic");
  sub->add_option("--budget-ms", v->budgetMs, "heuristic: RT budget in ms for hybrid-budget");
  sub->add_option("--threads", v->threads, "Worker threads (0 = all cores)");
  return [v] { return v->run(); };
}

}  // namespace tandem
