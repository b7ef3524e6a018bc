// tandem experiment NAME: regenerates an experiment in one command. An experiment is data: a
// JSON file (experiments/NAME.json in the source tree, or any path) whose "runner" picks the
// procedure — "sweep" (scenes x pipelines x a parameter sweep against cached references),
// "heuristic" (Walewski et al. 2019's Tables 5 and 6 and the ms-budget tracking), "taa" (TAA
// against a supersampled render), "hybrid-dof" (Tan et al. 2022's Table 2 and Figures 6-7),
// "foveated" (Peres 2022) or "interleaved" (Foster 2015). Command-line options override the file's
// settings. Every run writes results.md, CSV, PNG plots and index.html.
#include <cstdio>
#include <memory>

#include "cli_options.h"
#include "core/error.h"
#include "eval/experiments/experiment_runner.h"
#include "verbs.h"

namespace tandem {

namespace {

struct ExperimentVerb {
  bool list = false;
  ExperimentRequest r;

  int run() {
    if (r.threads < 0 || r.threads > 4096)
      throw InputError("command line", "--threads", "must be in [0, 4096]");
    RenderOptions ro;
    ro.threads = r.threads;
    auto limit = limitThreads(ro);
    if (list || r.name.empty()) {
      for (const auto& [name, title] : listExperiments())
        std::printf("%-22s %s\n", name.c_str(), title.c_str());
      return r.name.empty() && !list ? 1 : 0;
    }
    return runExperiment(r);
  }
};

}  // namespace

VerbRunner addExperimentVerb(CLI::App& app) {
  auto v = std::make_shared<ExperimentVerb>();
  const char* env = std::getenv("TANDEM_REFERENCE_CACHE");
  v->r.o.cache = env && *env ? env : "out/reference-cache";
  CLI::App* sub = app.add_subcommand(
      "experiment", "Run an experiment (experiments/NAME.json or a file): tables, plots, index");
  sub->add_option("name", v->r.name, "Experiment name (see --list) or JSON file");
  sub->add_flag("--list", v->list, "List the built-in experiments");
  sub->add_option("--out", v->r.o.out, "Output folder (default out/experiment-NAME)");
  sub->add_option("--scenes", v->r.o.scenes, "Override the scenes (names or files)")
      ->delimiter(',');
  sub->add_option("--width", v->r.o.width, "Override the image width");
  sub->add_option("--height", v->r.o.height, "Override the image height");
  sub->add_option("--warmup", v->r.o.warmup, "Override the untimed frames before measuring");
  sub->add_option("--frames", v->r.o.frames, "sweep: timed frames per render (median)");
  sub->add_option("--spp", v->r.o.spp, "sweep: reference samples per pixel");
  sub->add_option("--cache", v->r.o.cache,
                  "Reference cache folder (default $TANDEM_REFERENCE_CACHE or "
                  "out/reference-cache)");
  sub->add_flag("--no-cache", v->r.o.noCache, "Render references even when cached");
  sub->add_option("--static-frames", v->r.staticFrames, "heuristic: timed frames of each shot");
  sub->add_option("--path-frames", v->r.pathFrames, "heuristic: frames along the camera path");
  sub->add_option("--budget", v->r.budget, "heuristic: T in cost units for hybrid-heuristic");
  sub->add_option("--budget-ms", v->r.budgetMs, "heuristic: RT budget in ms for hybrid-budget");
  sub->add_option("--threads", v->r.threads, "Worker threads (0 = all cores)");
  sub->add_option("--device", v->r.device,
                  "auto (a GPU when there is one, else the CPU), cpu, or gpu: where the "
                  "experiment's renders run (passes without a GPU version on the CPU)");
  return [v] { return v->run(); };
}

}  // namespace tandem
