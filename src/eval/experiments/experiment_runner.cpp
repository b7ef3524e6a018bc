#include "eval/experiments/experiment_runner.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "eval/experiments/experiment_dof.h"
#include "eval/experiments/experiment_foveated.h"
#include "eval/experiments/experiment_gallery.h"
#include "eval/experiments/experiment_heuristic.h"
#include "eval/experiments/experiment_interleaved.h"
#include "eval/experiments/experiment_taa.h"
#include "pipeline/renderer.h"

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

namespace {

// The command line's overrides of an experiment file, each applied only where it was given.
struct Overrides {
  const ExperimentRequest& r;
  const fs::path& file;
  std::string out() const {
    return r.o.out.empty() ? "out/experiment-" + file.stem().string() : r.o.out;
  }
  std::string cache() const { return r.o.noCache ? "" : r.o.cache; }
  void size(int& width, int& height) const {
    if (r.o.width) width = r.o.width;
    if (r.o.height) height = r.o.height;
  }
  void warmup(int& v) const { v = r.o.warmup >= 0 ? r.o.warmup : v; }
  void frames(int& v) const { v = r.o.frames ? r.o.frames : v; }
  void spp(int& v) const { v = r.o.spp ? r.o.spp : v; }
  void scenes(std::vector<std::string>& v) const { v = r.o.scenes.empty() ? v : r.o.scenes; }
  void noScenes(const std::string& what) const {
    if (!r.o.scenes.empty()) throw InputError("command line", "--scenes", "not for " + what);
  }
};

// Where a runner's options take the common flags (null or empty: the runner has no such setting).
template <class O>
struct Targets {
  int O::*width = nullptr;
  int O::*height = nullptr;
  int O::*warmup = nullptr;
  std::vector<int O::*> frames{}, spp{};
};

template <class O>
O withOverrides(O o, const Overrides& v, const Targets<O>& t) {
  o.out = v.out();
  if (t.width) v.size(o.*t.width, o.*t.height);
  if (t.warmup) v.warmup(o.*t.warmup);
  for (int O::*f : t.frames) v.frames(o.*f);
  for (int O::*s : t.spp) v.spp(o.*s);
  return o;
}

int heuristic(const nlohmann::json& j, const Overrides& v) {
  using O = HeuristicExperimentOptions;
  O o = withOverrides(heuristicOptionsFromJson(j, v.file.string()), v,
                      {.width = &O::width, .height = &O::height, .warmup = &O::warmup});
  v.scenes(o.scenes);
  const ExperimentRequest& r = v.r;  // the heuristic's own overrides, range-checked by it
  if (r.staticFrames != -1) o.staticFrames = r.staticFrames;
  if (r.pathFrames != -1) o.pathFrames = r.pathFrames;
  if (r.budget >= 0) o.budget = r.budget;
  if (r.budgetMs >= 0) o.budgetMs = r.budgetMs;
  o.threads = r.threads;
  return runHeuristicExperiment(o);
}

int taa(const nlohmann::json& j, const Overrides& v) {
  using O = TaaExperimentOptions;
  O o = withOverrides(taaOptionsFromJson(j, v.file.string()), v,
                      {.width = &O::width, .height = &O::height, .frames = {&O::staticFrames}});
  v.scenes(o.scenes);
  if (v.r.pathFrames != -1) o.pathFrames = v.r.pathFrames;
  return runTaaExperiment(o);
}

int hybridDof(const nlohmann::json& j, const Overrides& v) {
  using O = DofExperimentOptions;
  O o = withOverrides(dofOptionsFromJson(j, v.file.string()), v,
                      {.width = &O::width,
                       .height = &O::height,
                       .warmup = &O::warmup,
                       .frames = {&O::frames},
                       .spp = {&O::referenceSpp, &O::pathReferenceSpp}});
  o.cache = v.cache();
  return runDofExperiment(o);
}

int foveated(const nlohmann::json& j, const Overrides& v) {
  using O = FoveatedExperimentOptions;
  O o = withOverrides(foveatedOptionsFromJson(j, v.file.string()), v,
                      {.width = &O::qualityWidth,
                       .height = &O::qualityHeight,
                       .warmup = &O::warmup,
                       .frames = {&O::fhdFrames, &O::quest2Frames},
                       .spp = {&O::referenceSpp}});
  o.cache = v.cache();
  return runFoveatedExperiment(o);
}

int interleaved(const nlohmann::json& j, const Overrides& v) {
  v.noScenes("interleaved");
  using O = InterleavedExperimentOptions;
  O o = withOverrides(interleavedOptionsFromJson(j, v.file.string()), v,
                      {.width = &O::width,
                       .height = &O::height,
                       .warmup = &O::timingWarmup,
                       .frames = {&O::timingFrames},
                       .spp = {&O::referenceSpp}});
  o.cache = v.cache();
  return runInterleavedExperiment(o);
}

int gallery(const nlohmann::json& j, const Overrides& v) {
  v.noScenes("a gallery");
  using O = GalleryOptions;
  O o = withOverrides(galleryOptionsFromJson(j, v.file.string()), v,
                      {.width = &O::width, .height = &O::height});
  if (v.r.o.frames) {
    o.frames = v.r.o.frames;
    for (GalleryRow& row : o.rows) row.frames = 0;  // --frames sets every row's
  }
  o.cache = v.cache();
  for (GalleryRow& row : o.rows) v.spp(row.groundTruth.spp);
  return runGallery(o);
}

}  // namespace

namespace {

// The overrides' ranges (0 or -1: not given), checked before anything runs; the CLI and Python
// both come through here.
std::string fmtNumber(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

void checkOverrides(const ExperimentRequest& r) {
  auto range = [&r](std::string field, double v, double unset, double lo, double hi) {
    if (!r.fromPython) {
      std::replace(field.begin(), field.end(), '_', '-');
      field = "--" + field;
    }
    if (v != unset && !(v >= lo && v <= hi))
      throw InputError(
          r.fromPython ? "experiment" : "command line", field,
          "must be in [" + fmtNumber(lo) + ", " + fmtNumber(hi) + "] (got " + fmtNumber(v) + ")");
  };
  range("width", r.o.width, 0, 1, 16384);
  range("height", r.o.height, 0, 1, 16384);
  range("warmup", r.o.warmup, -1, 0, 100000);
  range("frames", r.o.frames, 0, 1, 1000000);
  range("spp", r.o.spp, 0, 1, 1 << 20);
  range("static_frames", r.staticFrames, -1, 1, 1000000);
  range("path_frames", r.pathFrames, -1, 1, 1000000);
  range("threads", r.threads, 0, 1, 4096);
  range("budget", r.budget, -1, 0, 1e30);
  range("budget_ms", r.budgetMs, -1, 1e-3, 1e9);
}

// Moves what `from` holds into `to` (created), file by file, replacing files of the same name and
// leaving the rest of `to` as it was.
void publish(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const fs::directory_entry& e : fs::directory_iterator(from)) {
    const fs::path target = to / e.path().filename();
    if (e.is_directory() && !e.is_symlink()) {
      publish(e.path(), target);
    } else {
      fs::rename(e.path(), target);
    }
  }
}

int runStaged(const ExperimentRequest& r);

}  // namespace

void applyGpuFields(nlohmann::json& j, const std::string& file, bool hardwareGpu) {
  if (!j.contains("gpu")) return;
  const nlohmann::json g = j["gpu"];
  if (!g.is_object())
    throw InputError(file, "gpu", "expected an object of the fields a GPU renders with instead");
  for (auto it = g.begin(); it != g.end(); ++it)
    if (it.key() == "gpu" || it.key() == "runner" || !j.contains(it.key()))
      throw InputError(file, "gpu." + it.key(), "not a field of this experiment it could replace");
  j.erase("gpu");
  if (hardwareGpu)
    for (auto it = g.begin(); it != g.end(); ++it) j[it.key()] = it.value();
}

// Everything is written into a staging folder beside the output folder and moved into it only
// when the run succeeded: a run that fails, runs out of disk or is stopped leaves nothing behind,
// and what the output folder held before is replaced file by file, never removed.
int runExperiment(const ExperimentRequest& r) {
  checkOverrides(r);
  // Every render of the experiment (its runners make their own settings) on the device asked for.
  const char* deviceField = r.fromPython ? "device" : "--device";
  const std::string source = r.fromPython ? "experiment()" : "command line";
  const DeviceChoice choice = parseDeviceChoice(r.device, source, deviceField);
  const ScopedRenderDevice device(GpuDevice::forChoice(choice, source + ": " + deviceField));
  if (const std::shared_ptr<GpuDevice> gpu = defaultRenderDevice())
    std::fprintf(stderr, "tandem: device: %s (%s)\n", gpu->info().name.c_str(),
                 gpu->info().type.c_str());
  fs::path out = fs::path(experimentOutDir(r)).lexically_normal();
  if (out.filename().empty()) out = out.parent_path();
  fs::path staging = out;
  staging += ".partial";
  std::error_code ec;
  fs::remove_all(staging, ec);  // a crashed run's
  ExperimentRequest staged = r;
  staged.o.out = staging.string();
  int status = 0;
  try {
    status = runStaged(staged);
    if (status == 0) publish(staging, out);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(staging, ec);
    throw InputError(out.string(), "",
                     std::string("cannot write the results: ") + e.code().message());
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  fs::remove_all(staging, ec);
  if (status == 0) std::printf("wrote %s (index.html, results.md)\n", out.string().c_str());
  return status;
}

namespace {

int runStaged(const ExperimentRequest& r) {
  const fs::path file = resolveExperiment(r.name);
  std::ifstream in(file);
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError(file.string(), "", "not a JSON object");
  const std::shared_ptr<GpuDevice> gpu = defaultRenderDevice();
  applyGpuFields(j, file.string(), gpu && gpu->info().hardware);
  const std::string runner = j.value("runner", "sweep");
  const Overrides v{r, file};
  // The flags of one runner are an error elsewhere, not silently ignored.
  if (runner != "heuristic" && (r.staticFrames != -1 || r.budget >= 0 || r.budgetMs >= 0))
    throw InputError("command line", "--static-frames/--budget/--budget-ms",
                     "apply to the heuristic runner only");
  if (runner != "heuristic" && runner != "taa" && r.pathFrames != -1)
    throw InputError("command line", "--path-frames", "applies to the heuristic and taa runners");
  if (runner == "heuristic") return heuristic(j, v);
  if (runner == "taa") return taa(j, v);
  if (runner == "hybrid-dof") return hybridDof(j, v);
  if (runner == "foveated") return foveated(j, v);
  if (runner == "interleaved") return interleaved(j, v);
  if (runner == "gallery") return gallery(j, v);
  if (runner != "sweep")
    throw InputError(file.string(), "runner",
                     "'" + runner +
                         "' is not sweep, heuristic, taa, hybrid-dof, foveated, interleaved or "
                         "gallery");
  return runSweepExperiment(j, file.string(), r.o);
}

}  // namespace

}  // namespace tandem
