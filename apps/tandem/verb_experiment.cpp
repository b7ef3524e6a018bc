// tandem experiment: regenerates a paper's experiments in one command (tables, CSV, PNGs).
// Sub-commands: heuristic (seed 002).
#include <memory>

#include "cli_options.h"
#include "experiment_heuristic.h"
#include "verbs.h"

namespace tandem {

VerbRunner addExperimentVerb(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("experiment", "Reproduce a paper's experiments");
  sub->require_subcommand(1);
  auto h = std::make_shared<HeuristicExperimentOptions>();
  CLI::App* heur = sub->add_subcommand(
      "heuristic", "Seed 002: Table 5 (static shots), Table 6 (camera path), ms-budget tracking");
  heur->add_option("--out", h->out, "Output folder (results.md, CSV, PNGs)");
  heur->add_option("--scenes", h->scenes,
                   "Scenes (built-in names or files); default: spheres, atrium_spheres, "
                   "atrium_bunny, cornell_spheres")
      ->delimiter(',');
  heur->add_option("--width", h->width, "Image width");
  heur->add_option("--height", h->height, "Image height");
  heur->add_option("--warmup", h->warmup, "Untimed frames before each measurement");
  heur->add_option("--static-frames", h->staticFrames, "Timed frames of each static shot");
  heur->add_option("--path-frames", h->pathFrames, "Frames along the camera path (Table 6)");
  heur->add_option("--budget", h->budget, "T in cost units for hybrid-heuristic");
  heur->add_option("--budget-ms", h->budgetMs, "RT budget in ms for hybrid-budget");
  heur->add_option("--threads", h->threads, "Worker threads (0 = all cores)");
  return [h, heur]() {
    if (!heur->parsed()) return 1;
    RenderOptions ro;
    ro.threads = h->threads;
    if (h->threads < 0 || h->threads > 4096)
      throw InputError("command line", "--threads", "must be in [0, 4096]");
    auto limit = limitThreads(ro);
    return runHeuristicExperiment(*h);
  };
}

}  // namespace tandem
