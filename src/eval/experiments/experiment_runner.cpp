#include "eval/experiments/experiment_runner.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "eval/experiments/experiment_dof.h"
#include "eval/experiments/experiment_foveated.h"
#include "eval/experiments/experiment_gallery.h"
#include "eval/experiments/experiment_heuristic.h"
#include "eval/experiments/experiment_interleaved.h"
#include "eval/experiments/experiment_taa.h"

#ifndef TANDEM_SOURCE_DIR
#define TANDEM_SOURCE_DIR "."
#endif

namespace tandem {
namespace fs = std::filesystem;

fs::path experimentsDir() {
  return fs::path(TANDEM_SOURCE_DIR) / "experiments";
}

fs::path resolveExperiment(const std::string& name) {
  if (fs::exists(name) && fs::is_regular_file(name)) return name;
  const fs::path p = experimentsDir() / (name + ".json");
  if (fs::exists(p)) return p;
  std::string known;
  for (const auto& [n, title] : listExperiments()) known += " " + n;
  throw InputError(name, "",
                   "not an experiment file and not a built-in experiment (have:" + known + ")");
}

std::vector<std::pair<std::string, std::string>> listExperiments() {
  std::vector<std::pair<std::string, std::string>> out;
  if (!fs::exists(experimentsDir())) return out;
  for (const auto& e : fs::directory_iterator(experimentsDir())) {
    if (e.path().extension() != ".json") continue;
    std::ifstream in(e.path());
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    out.push_back({e.path().stem().string(),
                   j.is_object() ? j.value("title", "") : std::string("(unreadable)")});
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string experimentOutDir(const ExperimentRequest& r) {
  return r.o.out.empty() ? "out/experiment-" + resolveExperiment(r.name).stem().string() : r.o.out;
}

int runExperiment(const ExperimentRequest& r) {
  const fs::path file = resolveExperiment(r.name);
  std::ifstream in(file);
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError(file.string(), "", "not a JSON object");
  const std::string runner = j.value("runner", "sweep");
  if (runner == "heuristic") {
    HeuristicExperimentOptions ho = heuristicOptionsFromJson(j, file.string());
    ho.out = r.o.out.empty() ? "out/experiment-" + file.stem().string() : r.o.out;
    if (!r.o.scenes.empty()) ho.scenes = r.o.scenes;
    if (r.o.width) ho.width = r.o.width;
    if (r.o.height) ho.height = r.o.height;
    if (r.o.warmup >= 0) ho.warmup = r.o.warmup;
    if (r.staticFrames != -1) ho.staticFrames = r.staticFrames;  // range-checked by the runner
    if (r.pathFrames != -1) ho.pathFrames = r.pathFrames;
    if (r.budget >= 0) ho.budget = r.budget;
    if (r.budgetMs >= 0) ho.budgetMs = r.budgetMs;
    ho.threads = r.threads;
    return runHeuristicExperiment(ho);
  }
  if (runner == "taa") {
    TaaExperimentOptions to = taaOptionsFromJson(j, file.string());
    to.out = r.o.out.empty() ? "out/experiment-" + file.stem().string() : r.o.out;
    if (!r.o.scenes.empty()) to.scenes = r.o.scenes;
    if (r.o.width) to.width = r.o.width;
    if (r.o.height) to.height = r.o.height;
    if (r.o.frames) to.staticFrames = r.o.frames;
    if (r.pathFrames != -1) to.pathFrames = r.pathFrames;
    return runTaaExperiment(to);
  }
  if (runner == "hybrid-dof") {
    DofExperimentOptions d = dofOptionsFromJson(j, file.string());
    d.out = r.o.out.empty() ? "out/experiment-" + file.stem().string() : r.o.out;
    d.cache = r.o.noCache ? "" : r.o.cache;
    if (r.o.width) d.width = r.o.width;
    if (r.o.height) d.height = r.o.height;
    if (r.o.warmup >= 0) d.warmup = r.o.warmup;
    if (r.o.frames) d.frames = r.o.frames;
    if (r.o.spp) d.referenceSpp = d.pathReferenceSpp = r.o.spp;
    return runDofExperiment(d);
  }
  if (runner == "foveated") {
    FoveatedExperimentOptions fo = foveatedOptionsFromJson(j, file.string());
    fo.out = r.o.out.empty() ? "out/experiment-" + file.stem().string() : r.o.out;
    fo.cache = r.o.noCache ? "" : r.o.cache;
    if (r.o.width) fo.qualityWidth = r.o.width;
    if (r.o.height) fo.qualityHeight = r.o.height;
    if (r.o.warmup >= 0) fo.warmup = r.o.warmup;
    if (r.o.frames) fo.fhdFrames = fo.quest2Frames = r.o.frames;
    if (r.o.spp) fo.referenceSpp = r.o.spp;
    return runFoveatedExperiment(fo);
  }
  if (runner == "interleaved") {
    InterleavedExperimentOptions io = interleavedOptionsFromJson(j, file.string());
    io.out = r.o.out.empty() ? "out/experiment-" + file.stem().string() : r.o.out;
    io.cache = r.o.noCache ? "" : r.o.cache;
    if (r.o.width) io.width = r.o.width;
    if (r.o.height) io.height = r.o.height;
    if (r.o.warmup >= 0) io.timingWarmup = r.o.warmup;
    if (r.o.frames) io.timingFrames = r.o.frames;
    if (r.o.spp) io.referenceSpp = r.o.spp;
    if (!r.o.scenes.empty()) throw InputError("command line", "--scenes", "not for interleaved");
    return runInterleavedExperiment(io);
  }
  if (runner == "gallery") {
    GalleryOptions go = galleryOptionsFromJson(j, file.string());
    go.out = r.o.out.empty() ? "out/experiment-" + file.stem().string() : r.o.out;
    if (r.o.width) go.width = r.o.width;
    if (r.o.height) go.height = r.o.height;
    if (r.o.frames) {
      go.frames = r.o.frames;
      for (GalleryRow& row : go.rows) row.frames = 0;  // --frames sets every row's
    }
    if (!r.o.scenes.empty()) throw InputError("command line", "--scenes", "not for a gallery");
    go.cache = r.o.noCache ? "" : r.o.cache;
    if (r.o.spp)
      for (GalleryRow& row : go.rows) row.groundTruth.spp = r.o.spp;
    return runGallery(go);
  }
  if (runner != "sweep")
    throw InputError(file.string(), "runner",
                     "'" + runner +
                         "' is not sweep, heuristic, taa, hybrid-dof, foveated, interleaved or "
                         "gallery");
  if (r.staticFrames != -1 || r.pathFrames != -1 || r.budget >= 0 || r.budgetMs >= 0)
    throw InputError("command line", "--static-frames/--path-frames/--r.budget/--r.budget-ms",
                     "apply to the heuristic runner only");
  return runSweepExperiment(j, file.string(), r.o);
}

}  // namespace tandem
