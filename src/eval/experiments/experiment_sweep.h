// Data-driven experiments (`tandem experiment NAME`, NAME = experiments/NAME.json or a file):
// scenes x pipelines x an optional parameter sweep, each compared against a cached path-traced
// reference of the same shot by RMSE, PSNR, SSIM and FLIP, with frame times; written as CSV,
// Markdown, gnuplot PNG plots (each metric against the swept parameter) and an index page.
// The file format is in docs/experiments.md.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tandem {

// Command-line values that override the experiment file's (0 / empty: keep the file's).
struct ExperimentOverrides {
  std::string out, cache;
  std::vector<std::string> scenes;
  int width = 0, height = 0, warmup = -1, frames = 0, spp = 0;
  bool noCache = false;
};

// Runs a `"runner": "sweep"` experiment read from `file`; throws InputError naming the field.
int runSweepExperiment(const nlohmann::json& j, const std::string& file,
                       const ExperimentOverrides& o);

}  // namespace tandem
