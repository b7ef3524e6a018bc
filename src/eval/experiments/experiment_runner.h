// Running an experiment by name: experiments/NAME.json in the source tree (or any JSON file),
// whose "runner" picks the procedure — "sweep" (scenes x pipelines x a parameter sweep against
// cached references), "heuristic" (Walewski et al. 2019), "taa", "hybrid-dof" (Tan et al. 2022),
// "foveated" (Peres 2022), "interleaved" (Foster 2015) or "gallery" (the demo). The request's
// overrides replace the file's settings. `tandem experiment` and the Python module both call it.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/experiments/experiment_sweep.h"

namespace tandem {

struct ExperimentRequest {
  std::string name;  // experiments/NAME.json, or a JSON file
  ExperimentOverrides o;
  int staticFrames = -1, pathFrames = -1, threads = 0;  // -1: not given
  double budget = -1, budgetMs = -1;                    // heuristic runner; -1: not given
  std::string device = "auto";  // where its renders run: auto, cpu or gpu (passes without one: CPU)
  // Who asks, for error messages: the CLI's options are "--width", Python's arguments "width".
  bool fromPython = false;
};

// The folder of the built-in experiments (experiments/ in the source tree).
std::filesystem::path experimentsDir();
// The experiment file `name` stands for; an InputError listing the built-in ones otherwise.
std::filesystem::path resolveExperiment(const std::string& name);
// Built-in experiments: name and title.
std::vector<std::pair<std::string, std::string>> listExperiments();
// Where the request writes its results (its `out`, or out/experiment-NAME).
std::string experimentOutDir(const ExperimentRequest& r);
// Runs it; returns the exit status (0 on success). Bad files and overrides throw InputError.
int runExperiment(const ExperimentRequest& r);
// The papers' real-time sizes where a GPU renders: an experiment's "gpu" object holds fields of
// the experiment (its sizes) that replace the file's own when `hardwareGpu` (a CPU, or a CPU
// Vulkan, keeps the file's). "gpu" is removed either way; a field it names that the experiment
// lacks is an InputError naming `file` and "gpu.FIELD".
void applyGpuFields(nlohmann::json& experiment, const std::string& file, bool hardwareGpu);

}  // namespace tandem
