// `tandem experiment heuristic`: Walewski et al. 2019's experiments, regenerated in one command.
//  - Table 5 shape: a static shot of each scene; RAST, HEUR, RAYT and FRAME ms (medians) for
//    hybrid-heuristic, FRAME for rt-only, their ratio, and SSIM/PSNR of hybrid-heuristic
//    against hybrid-all (what the budget costs in quality).
//  - Table 6 shape: mean frame time along the scene's camera path with the heuristic
//    (hybrid-heuristic) and without it (hybrid-all).
//  - The ms budget (hybrid-budget): the RT stage's time against the budget on every path frame,
//    and the share of frames within ±15 %.
// Writes results.md, table5.csv, table6.csv, budget_frames.csv and PNGs into the output folder.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tandem {

struct HeuristicExperimentOptions {
  std::string out = "out/experiment-heuristic";
  std::vector<std::string> scenes;  // built-in names or scene files; empty = the paper's four
  int width = 1280, height = 720;
  int warmup = 2;           // untimed frames before each measurement
  int staticFrames = 5;     // timed frames of the static shot (medians)
  int pathFrames = 200;     // frames along the camera path (Table 6)
  double budget = 2e6;      // T (cost units) for hybrid-heuristic
  double budgetMs = 50;     // RT budget for hybrid-budget
  double tolerance = 0.15;  // budget tracking band
  int threads = 0;
};

// The paper's four test scenes, in kind (paths relative to the source tree's scenes/).
std::vector<std::string> defaultHeuristicScenes();

// Reads the runner's settings from an experiment file (`"runner": "heuristic"`); scene files
// are relative to it. Throws InputError naming the field.
HeuristicExperimentOptions heuristicOptionsFromJson(const nlohmann::json& j,
                                                    const std::string& file);

// Runs the experiment; throws InputError on bad options or scenes. Returns 0.
int runHeuristicExperiment(const HeuristicExperimentOptions& o);

}  // namespace tandem
