#include "eval/experiments/experiment_taa.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/image_filters.h"
#include "core/image_io.h"
#include "core/json_fields.h"
#include "eval/experiments/experiment_report.h"
#include "eval/metrics/metrics.h"
#include "eval/reference/supersample.h"
#include "pipeline/aov.h"
#include "pipeline/pass_times.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {

namespace fs = std::filesystem;

TaaExperimentOptions taaOptionsFromJson(const nlohmann::json& j, const std::string& file) {
  JsonFields f(j, file, "");
  TaaExperimentOptions o;
  f.string("title", "");
  f.string("runner", "taa");
  if (f.has("scenes")) {
    const Json& s = f.raw("scenes");
    if (!s.is_array() || s.empty()) f.fail("scenes", "expected a non-empty array of scenes");
    o.scenes.clear();
    for (const Json& x : s) {
      if (!x.is_string()) f.fail("scenes", "expected scene names or files");
      o.scenes.push_back(x.get<std::string>());
    }
  }
  if (f.has("pairs")) {
    const Json& p = f.raw("pairs");
    if (!p.is_array() || p.empty()) f.fail("pairs", "expected [[without, with TAA], ...]");
    o.pairs.clear();
    for (const Json& x : p) {
      if (!x.is_array() || x.size() != 2 || !x[0].is_string() || !x[1].is_string())
        f.fail("pairs", "each pair is [pipeline without TAA, pipeline with TAA]");
      o.pairs.push_back({x[0].get<std::string>(), x[1].get<std::string>()});
    }
  }
  o.width = f.integer("width", o.width, 8, 16384);
  o.height = f.integer("height", o.height, 8, 16384);
  o.staticFrames = f.integer("staticFrames", o.staticFrames, 4, 100000);
  o.supersample = f.integer("supersample", o.supersample, 1, 64);
  o.pathFrames = f.integer("pathFrames", o.pathFrames, 0, 100000);
  o.pathEvery = f.integer("pathEvery", o.pathEvery, 1, 100000);
  cropFromJson(f, o.crop);
  f.finish();
  return o;
}

namespace {

double meanAbsDiff(const Buffer& a, const Buffer& b) {
  double s = 0;
  for (size_t i = 0; i < a.data.size(); ++i) s += std::abs(double(a.data[i]) - double(b.data[i]));
  return a.data.empty() ? 0 : s / double(a.data.size());
}

// Flicker: the mean absolute change of the displayed image after last frame's image is moved
// along this frame's motion vectors (what motion explains is taken out; shimmer is left).
// Pixels whose source lies outside the image are skipped.
double compensatedChange(const Buffer& cur, const Buffer& prev, const Buffer& motion) {
  double s = 0;
  size_t n = 0;
  float p[4];
  for (int y = 0; y < cur.height; ++y)
    for (int x = 0; x < cur.width; ++x) {
      const float* m = motion.at(x, y);
      const float px = float(x) + 0.5f - m[0], py = float(y) + 0.5f - m[1];
      if (px < 0 || py < 0 || px >= float(cur.width) || py >= float(cur.height)) continue;
      sampleCatmullRom(prev, px, py, p);
      for (int c = 0; c < 3; ++c) s += std::abs(double(cur.at(x, y)[c]) - double(p[c]));
      n += 3;
    }
  return n ? s / double(n) : 0.0;
}

double passMedian(std::vector<double>& v) {
  return v.empty() ? 0.0 : summarize(v).median;
}

// Static shot: the base pipeline, its TAA twin and the base with the same jitter, against the
// base supersampled (same shading).
void staticShot(const TaaExperimentOptions& o, const Scene& scene, const std::string& label,
                const CameraDesc& cam, const std::string& basePipe, const std::string& taaPipe,
                ExperimentReport& report, std::vector<std::vector<std::string>>& staticRows) {
  const RenderSettings rs{.width = o.width, .height = o.height};
  const int n = o.supersample;
  const Buffer truth = visualizeBuffer(supersample(scene, basePipe, cam, rs, n));
  Renderer base(scene, Pipeline::load(basePipe), rs), taa(scene, Pipeline::load(taaPipe), rs),
      jittered(scene, Pipeline::load(basePipe), rs);
  for (Renderer* r : {&base, &taa, &jittered}) r->keepOnDevice();  // timed; outputs fetched
  base.renderFrame(0, cam);
  const Buffer aliased = base.output();
  Buffer lastTaa, lastJit;
  double taaChange = 0, jitChange = 0;
  int measured = 0;
  std::vector<double> taaMs, taaFrameMs, baseFrameMs;
  for (int i = 0; i < o.staticFrames; ++i) {
    const FrameTimings ft = taa.renderFrame(0, cam);
    jittered.renderFrame(0, cam, taa.context().jitter);
    const Buffer a = taa.output(), b = jittered.output();
    if (i >= o.staticFrames / 2) {
      taaChange += meanAbsDiff(a, lastTaa);
      jitChange += meanAbsDiff(b, lastJit);
      ++measured;
      taaFrameMs.push_back(ft.totalMs);
      taaMs.push_back(PassTimes(taa.pipeline(), ft).ofType("taa"));
      baseFrameMs.push_back(base.renderFrame(0, cam).totalMs);
    }
    lastTaa = a;
    lastJit = b;
  }
  const std::string stem = label + "_" + taa.pipeline().name;
  writePng((fs::path(o.out) / (stem + "_crop_aliased.png")).string(), cropOf(aliased, o.crop));
  writePng((fs::path(o.out) / (stem + "_crop_taa.png")).string(), cropOf(lastTaa, o.crop));
  writePng((fs::path(o.out) / (stem + "_crop_supersampled.png")).string(), cropOf(truth, o.crop));
  report.image(stem + "_crop_aliased.png", label + ": " + basePipe + " (1 spp)");
  report.image(stem + "_crop_taa.png",
               label + ": " + taaPipe + " after " + std::to_string(o.staticFrames) + " frames");
  report.image(stem + "_crop_supersampled.png",
               label + ": " + basePipe + " supersampled " + std::to_string(n * n) + " spp");
  staticRows.push_back({label, basePipe, fmt(ssim(aliased, truth), 4), fmt(psnr(aliased, truth), 2),
                        "0 (no jitter)", "—", fmt(passMedian(baseFrameMs), 1)});
  staticRows.push_back({label, taaPipe, fmt(ssim(lastTaa, truth), 4), fmt(psnr(lastTaa, truth), 2),
                        fmt(taaChange / measured, 5), fmt(passMedian(taaMs), 2),
                        fmt(passMedian(taaFrameMs), 1)});
  staticRows.push_back({label, basePipe + " + the same jitter, no TAA", "—", "—",
                        fmt(jitChange / measured, 5), "—", "—"});
}

// Along the camera path: each pipeline flies it from a fresh start, in real time (30 fps over
// the path's duration) unless the file gives a frame count.
void cameraPath(const TaaExperimentOptions& o, const Scene& scene, const std::string& label,
                const CameraDesc& cam, const std::string& basePipe, const std::string& taaPipe,
                ExperimentReport& report, std::vector<std::vector<std::string>>& pathRows) {
  const RenderSettings rs{.width = o.width, .height = o.height};
  const int n = o.supersample;
  // Along the camera path: each pipeline flies it from a fresh start, in real time (30 fps
  // over the path's duration) unless the file gives a frame count.
  const int pathFrames =
      o.pathFrames > 0 ? o.pathFrames
      : scene.cameraPath.size() > 1
          ? std::max(2, int(std::lround(30.0f * (scene.cameraPath.back().time -
                                                 scene.cameraPath.front().time))))
          : 48;
  Renderer basePath(scene, Pipeline::load(basePipe), rs),
      taaPath(scene, Pipeline::load(taaPipe), rs);
  for (Renderer* r : {&basePath, &taaPath}) r->keepOnDevice();
  double baseSsim = 0, taaSsim = 0, baseChange = 0, taaPathChange = 0;
  int compared = 0;
  Buffer prevBase, prevTaa;
  for (int f = 0; f < pathFrames; ++f) {
    const CameraDesc c = pathCamera(scene, cam, f, pathFrames);
    basePath.renderFrame(f, c);
    taaPath.renderFrame(f, c);
    const Buffer b = basePath.output(), t = taaPath.output();
    if (f > 0) {
      baseChange += compensatedChange(b, prevBase, basePath.fetch("motion"));
      taaPathChange += compensatedChange(t, prevTaa, taaPath.fetch("motion"));
    }
    prevBase = b;
    prevTaa = t;
    if (f > 0 && f % o.pathEvery == 0) {
      const Buffer truthF = visualizeBuffer(supersample(scene, basePipe, c, rs, n));
      baseSsim += ssim(b, truthF);
      taaSsim += ssim(t, truthF);
      ++compared;
      if (compared == 1) {
        const std::string s = label + "_path" + std::to_string(f) + "_" + taaPath.pipeline().name;
        writePng((fs::path(o.out) / (s + "_crop_aliased.png")).string(), cropOf(b, o.crop));
        writePng((fs::path(o.out) / (s + "_crop_taa.png")).string(), cropOf(t, o.crop));
        report.image(s + "_crop_aliased.png",
                     label + " path frame " + std::to_string(f) + ": " + basePipe);
        report.image(s + "_crop_taa.png",
                     label + " path frame " + std::to_string(f) + ": " + taaPipe);
      }
    }
  }
  const double steps = double(std::max(pathFrames - 1, 1));
  pathRows.push_back(
      {label, basePipe, fmt(compared ? baseSsim / compared : 0, 4), fmt(baseChange / steps, 5)});
  pathRows.push_back(
      {label, taaPipe, fmt(compared ? taaSsim / compared : 0, 4), fmt(taaPathChange / steps, 5)});
}

}  // namespace

int runTaaExperiment(const TaaExperimentOptions& o) {
  std::vector<Scene> scenes;
  for (const std::string& spec : o.scenes) scenes.push_back(loadScene(spec));
  for (const auto& [a, b] : o.pairs) {
    Pipeline::load(a);
    Pipeline::load(b);
  }
  fs::create_directories(o.out);
  ExperimentReport report(o.out, "TAA against a supersampled render");
  const int n = o.supersample;
  std::vector<std::vector<std::string>> staticRows, pathRows;
  for (size_t si = 0; si < scenes.size(); ++si) {
    const Scene& scene = scenes[si];
    const std::string label = sceneLabel(o.scenes[si]);
    const CameraDesc cam = defaultCamera(scene);
    for (const auto& [basePipe, taaPipe] : o.pairs) {
      std::printf("experiment taa: %s, %s vs %s\n", label.c_str(), basePipe.c_str(),
                  taaPipe.c_str());
      std::fflush(stdout);
      staticShot(o, scene, label, cam, basePipe, taaPipe, report, staticRows);
      cameraPath(o, scene, label, cam, basePipe, taaPipe, report, pathRows);
    }
  }
  report.markdown("Ground truth: the pipeline without TAA supersampled with " +
                  std::to_string(n * n) +
                  " sub-pixel offsets (same shading and lights). Images compared as displayed "
                  "(tonemapped, sRGB). Frame-to-frame change: mean absolute difference per "
                  "channel of consecutive displayed frames; along the path, after last frame's "
                  "image is moved along the motion vectors (Catmull-Rom), so what remains is "
                  "flicker (shimmer), not motion.\n\n");
  report.table("static",
               {"scene", "pipeline", "SSIM vs supersampled", "PSNR dB", "frame-to-frame change",
                "taa ms", "frame ms"},
               staticRows);
  report.table("path",
               {"scene", "pipeline", "mean SSIM vs supersampled (sampled frames)",
                "flicker: mean change after motion compensation"},
               pathRows);
  char settings[256];
  const std::string path =
      o.pathFrames > 0 ? std::to_string(o.pathFrames) + " path frames" : "the path in real time";
  std::snprintf(settings, sizeof settings,
                "%dx%d, %d static frames, %d x %d supersampling, %s (every %d-th frame compared)",
                o.width, o.height, o.staticFrames, n, n, path.c_str(), o.pathEvery);
  report.write(settings);
  return 0;
}

}  // namespace tandem
