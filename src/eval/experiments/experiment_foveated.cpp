#include "eval/experiments/experiment_foveated.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/image_io.h"
#include "core/json_fields.h"
#include "eval/experiments/experiment_report.h"
#include "eval/metrics/flip.h"
#include "eval/metrics/metrics.h"
#include "eval/reference/reference_cache.h"
#include "passes/foveated/foveated_pt.h"
#include "passes/foveated/foveation.h"
#include "passes/foveated/foveation_map.h"
#include "passes/foveated/nh_denoise.h"
#include "pipeline/aov.h"
#include "pipeline/pass_edit.h"
#include "pipeline/pass_times.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {

namespace fs = std::filesystem;

FoveatedExperimentOptions foveatedOptionsFromJson(const nlohmann::json& j,
                                                  const std::string& file) {
  JsonFields f(j, file, "");
  FoveatedExperimentOptions o;
  f.string("title", "");
  f.string("description", "");
  f.string("runner", "foveated");
  scenePairsFromJson(f, o.sceneLabels, o.scenes);
  if (f.has("resolutions")) {
    o.resolutions.clear();
    for (const Json& r : f.raw("resolutions")) {
      if (!r.is_string() || (r != "fhd" && r != "quest2"))
        f.fail("resolutions", "expected names out of fhd, quest2");
      o.resolutions.push_back(r.get<std::string>());
    }
  }
  o.warmup = f.integer("warmup", o.warmup, 0, 100000);
  o.fhdFrames = f.integer("fhdFrames", o.fhdFrames, 1, 100000);
  o.quest2Frames = f.integer("quest2Frames", o.quest2Frames, 1, 100000);
  o.qualityWidth = f.integer("qualityWidth", o.qualityWidth, 8, 16384);
  o.qualityHeight = f.integer("qualityHeight", o.qualityHeight, 8, 16384);
  o.referenceSpp = f.integer("referenceSpp", o.referenceSpp, 1, 1 << 20);
  o.temporalFrames = f.integer("temporalFrames", o.temporalFrames, 1, 100000);
  o.pathWidth = f.integer("pathWidth", o.pathWidth, 8, 16384);
  o.pathHeight = f.integer("pathHeight", o.pathHeight, 8, 16384);
  o.pathReferenceSpp = f.integer("pathReferenceSpp", o.pathReferenceSpp, 0, 1 << 20);
  cropFromJson(f, o.crop);
  f.finish();
  return o;
}

namespace {

struct Resolution {
  std::string name;
  int width, height;  // per eye
  float r0, r1;       // the thesis' radii at that size
};

Resolution resolutionNamed(const std::string& n) {
  if (n == "quest2") return {"quest2", 1832, 1920, 265, 530};
  return {"fhd", 960, 1080, 144, 288};
}

// The thesis' three configurations and, beyond it, NH3LD with the periphery accumulated over
// frames (foveated-nh3ld-temporal: periphery_accumulation, the selection rotating each frame, the
// levels from the measured noise) and NH3LD with its level counts from the measured noise. Every
// row but the labelled ones filters only what direct_light's noise-free direct light leaves
// (nh_denoise.split = direct).
struct Config {
  const char *pipeline, *label, *file;
  PipelineEdits sets;
  int base = 0;  // the configuration its speed-up and SSIM are taken against (itself: a Base)
  bool temporal = false;  // accumulates over frames: measured after temporalFrames frames
  bool moving = false;    // also measured with the camera moving (besides the temporal ones)
};
const PipelineEdit kLevelsFromVariance = editPass<NHDenoisePass>(
    [](NHDenoiseSettings& d) { d.levelsFrom = NHDenoiseSettings::LevelsFrom::Variance; });
const PipelineEdit kVarianceWeight = editPass<NHDenoisePass>(
    [](NHDenoiseSettings& d) { d.colorWeight = NHDenoiseSettings::ColorWeight::Variance; });
const PipelineEdit kNoSplit =
    editPass<NHDenoisePass>([](NHDenoiseSettings& d) { d.split = NHDenoiseSettings::Split::None; });
const PipelineEdit kFixedLevels = editPass<NHDenoisePass>(
    [](NHDenoiseSettings& d) { d.levelsFrom = NHDenoiseSettings::LevelsFrom::Fixed; });
const PipelineEdit kFixedSelection =
    editPass<FoveationPass>([](FoveationSettings& f) { f.rotate = false; });
const PipelineEdit kUniformLights = editPass<FoveatedPTPass>(
    [](FoveatedPTSettings& p) { p.lightSelection = FoveatedPTSettings::LightSelection::Uniform; });

const std::vector<Config>& configs() {
  static const std::vector<Config> c = {
      {"foveated-base", "Base", "base", {}, 0, false, true},
      {"foveated-nh2ld", "NH2LD", "nh2ld", {}},
      {"foveated-nh3ld", "NH3LD", "nh3ld", {}, 0, false, true},
      {"foveated-nh3ld-temporal", "NH3LD + temporal", "nh3ld-temporal", {}, 0, true},
      {"foveated-nh3ld", "NH3LD, levels from variance", "nh3ld-variance", {kLevelsFromVariance}},
      // Beyond the thesis: the colour weight scaled by each pixel's measured noise.
      {"foveated-base",
       "Base, variance-guided colour weight",
       "base-varweight",
       {kVarianceWeight},
       5},
      {"foveated-nh3ld",
       "NH3LD, variance-guided colour weight",
       "nh3ld-varweight",
       {kVarianceWeight},
       5},
      // The thesis' own estimator and filter: lights picked uniformly, the whole estimate
      // filtered (no direct_light split).
      {"foveated-base",
       "Base, the thesis (lights picked uniformly, no direct split)",
       "base-uniform",
       {kUniformLights, kNoSplit},
       7},
      {"foveated-nh3ld",
       "NH3LD, the thesis (lights picked uniformly, no direct split)",
       "nh3ld-uniform",
       {kUniformLights, kNoSplit},
       7},
      // The accumulating NH3LD with the thesis' selection, the same map every frame (its unlisted
      // pixels never sampled while the camera stands still).
      {"foveated-nh3ld-temporal",
       "NH3LD + temporal, the thesis' fixed selection",
       "nh3ld-temporal-fixed",
       {kFixedSelection},
       0,
       true},
      // The thesis' filter on the grid's estimate: the whole estimate filtered.
      {"foveated-base",
       "Base, the thesis' filter (no direct split)",
       "base-nosplit",
       {kNoSplit},
       10},
      {"foveated-nh3ld",
       "NH3LD, the thesis' filter (no direct split)",
       "nh3ld-nosplit",
       {kNoSplit},
       10},
      {"foveated-nh3ld-temporal",
       "NH3LD + temporal, no direct split",
       "nh3ld-temporal-nosplit",
       {kNoSplit},
       10,
       true},
      // The accumulating NH3LD with the thesis' selection and level counts (2 / 3 / 5).
      {"foveated-nh3ld-temporal",
       "NH3LD + temporal, the thesis' fixed selection and levels",
       "nh3ld-temporal-thesis",
       {kFixedSelection, kFixedLevels},
       0,
       true}};
  return c;
}

// The configurations' labels joined by `sep`.
std::string configLabels(const char* sep) {
  std::string out;
  for (const Config& c : configs()) out += (out.empty() ? "" : sep) + std::string(c.label);
  return out;
}

Renderer makeRenderer(const Scene& scene, const char* pipeline, int w, int h,
                      const PipelineEdits& edits) {
  Pipeline p = Pipeline::load(pipeline);
  applyEdits(p, edits);
  RenderSettings rs{.width = w, .height = h};
  rs.stereo = scene.stereo;
  rs.stereo.enabled = true;
  Renderer r(scene, std::move(p), rs);
  r.keepOnDevice();  // timed: images read back after the frames (Renderer::output)
  return r;
}

// The same path tracer converged, without foveation or denoising (the thesis' reference), both
// eyes side by side, display-encoded.
Buffer convergedDualImage(const Scene& scene, const CameraDesc& cam, int w, int h, int spp,
                          const std::string& cache) {
  ReferenceJob job;
  job.scene = &scene;
  job.camera = job.shutterCamera = cam;
  job.width = w;
  job.height = h;
  job.stereo = scene.stereo;
  job.stereo.enabled = true;
  job.settings.spp = spp;
  job.settings.integrator = Integrator::DiffuseGI;
  job.settings.progress = true;
  return visualizeBuffer(referenceImage(job, cache).hdr);
}

// The pipelines' layers at an eye `height` rows tall (the FHD radii scaled, as scale_radii).
FoveationDesc scaledLayers(int height) {
  FoveationDesc d;
  d.r0 = 144.0f * float(height) / 1080.0f;
  d.r1 = 288.0f * float(height) / 1080.0f;
  return d;
}

// Mean of `map` (1 channel or the first) over the pixels of both eyes whose layer is `layer`.
double meanOverLayer(const Buffer& map, const FoveationMap& fm, int layer) {
  double sum = 0;
  size_t n = 0;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      if (fm.layer[size_t(y) * size_t(fm.width) + size_t(x % fm.width)] != layer) continue;
      sum += map.at(x, y)[0];
      ++n;
    }
  return n ? sum / double(n) : 0.0;
}

// Copies `src` (3 channels) into `dst` with its left edge at column ox.
void paste(Buffer& dst, const Buffer& src, int ox) {
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x)
      for (int k = 0; k < 3; ++k) dst.at(ox + x, y)[k] = src.at(x, y)[k];
}

// Per-pixel squared error averaged over channels (for RMSE per layer).
Buffer squaredError(const Buffer& a, const Buffer& b) {
  Buffer e(a.width, a.height, 1);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += std::pow(double(a.at(x, y)[k]) - b.at(x, y)[k], 2);
      e.at(x, y)[0] = float(s / 3.0);
    }
  return e;
}

// Table 2: the distribution of each resolution (the pipelines' defaults: p = 0.5, 4/3/2 spp).
void table2(const FoveatedExperimentOptions& o, ExperimentReport& report) {
  std::vector<std::vector<std::string>> t2;
  for (const std::string& rn : o.resolutions) {
    const Resolution r = resolutionNamed(rn);
    FoveationDesc d;
    d.r0 = r.r0;
    d.r1 = r.r1;
    const FoveationMap m = computeFoveation(r.width, r.height, d);
    const char* names[3] = {"Inner", "Middle", "Outer"};
    for (int L = 0; L < 3; ++L) {
      const FoveationLayerStats& s = m.layers[L];
      t2.push_back({rn + " (" + std::to_string(r.width) + "x" + std::to_string(r.height) + ")",
                    names[L], L < 2 ? fmt(s.radius, 0) : "-", std::to_string(s.area),
                    std::to_string(s.tableSamples()), std::to_string(s.spp),
                    std::to_string(s.listed), std::to_string(s.samples())});
    }
  }
  report.markdown(
      "### Table 2: region distribution per eye (p = 0.5)\n\nArea: the pixels of the layer "
      "(round(π r²) for the inner disc, the ring between for the middle). Samples and spp as the "
      "thesis prints them (samples = area x spp); listed and traced: what the selection toss "
      "keeps (the middle ring falls linearly from 1 at r0 to p at r1, the outer layer is p).\n\n");
  report.table("table2_distribution",
               {"resolution", "region", "radius (px)", "area (px)", "samples (area x spp)", "spp",
                "listed pixels", "traced samples"},
               t2);
}

// Table 4: mean ms per frame along the camera path; returns NH3LD's speed-ups over Base.
std::vector<double> table4(const FoveatedExperimentOptions& o, const std::vector<Scene>& scenes,
                           ExperimentReport& report) {
  const int kConfigCount = int(configs().size());
  std::vector<double> speedups;
  std::vector<std::vector<std::string>> t4;
  for (const std::string& rn : o.resolutions) {
    const Resolution r = resolutionNamed(rn);
    const int frames = rn == "quest2" ? o.quest2Frames : o.fhdFrames;
    const PipelineEdit radii = editPass<FoveationPass>([&](FoveationSettings& f) {
      f.scaleRadii = false;
      f.r0 = float(r.r0);
      f.r1 = float(r.r1);
    });
    for (size_t s = 0; s < scenes.size(); ++s) {
      std::vector<double> configMs(size_t(kConfigCount), 0.0);
      for (int c = 0; c < kConfigCount; ++c) {
        std::printf("experiment foveated: Table 4, %s, %s, %s\n", rn.c_str(),
                    o.sceneLabels[s].c_str(), configs()[size_t(c)].label);
        std::fflush(stdout);
        PipelineEdits sets = {radii};
        for (const PipelineEdit& x : configs()[size_t(c)].sets) sets.push_back(x);
        Renderer rd =
            makeRenderer(scenes[s], configs()[size_t(c)].pipeline, r.width, r.height, sets);
        const CameraDesc base = defaultCamera(scenes[s]);
        std::vector<double> ms, pt, dn;
        for (int f = 0; f < o.warmup + frames; ++f) {
          const CameraDesc cam = pathCamera(scenes[s], base, f, o.warmup + frames);
          const FrameTimings ft = rd.renderFrame(f, cam);
          if (f < o.warmup) continue;
          ms.push_back(ft.totalMs);
          const PassTimes times(rd.pipeline(), ft);
          if (times.has("foveated_pt")) pt.push_back(times.ofType("foveated_pt"));
          if (times.has("nh_denoise")) dn.push_back(times.ofType("nh_denoise"));
        }
        const double mean = summarize(ms).mean;
        configMs[size_t(c)] = mean;
        const int b = configs()[size_t(c)].base;
        const double speedup = configMs[size_t(b)] / mean;
        const Config& cf = configs()[size_t(c)];
        // NH3LD as the thesis runs it: its pipeline with no edit.
        if (std::string(cf.pipeline) == "foveated-nh3ld" && cf.sets.empty())
          speedups.push_back(speedup);
        t4.push_back({rn, o.sceneLabels[s], configs()[size_t(c)].label, fmt(mean, 1),
                      fmt(summarize(pt).mean, 1), fmt(summarize(dn).mean, 1),
                      b == c ? "-" : fmt(speedup, 2), std::to_string(frames)});
      }
    }
  }
  report.markdown("### Table 4 shape: mean ms per frame along the camera path (after " +
                  std::to_string(o.warmup) + " untimed frame(s))\n\n");
  report.table("table4_ms_per_frame",
               {"resolution", "scene", "renderer", "frame ms", "path tracing ms", "denoising ms",
                "speed-up over its Base", "frames"},
               t4);

  return speedups;
}

// Figure 17: the same crop of the left eye; Figure 18: FLIP maps side by side.
void figures17And18(const FoveatedExperimentOptions& o, size_t s, const Buffer& ref,
                    const std::vector<Buffer>& images, ExperimentReport& report) {
  const int qw = o.qualityWidth, qh = o.qualityHeight, kConfigCount = int(configs().size());
  const std::string label = sceneLabel(o.scenes[s]);
  const int crop[4] = {o.crop[0], o.crop[1], o.crop[2] ? o.crop[2] : qw / 2,
                       o.crop[3] ? o.crop[3] : qh / 3};
  const int cx = o.crop[2] ? crop[0] : qw / 4, cy = o.crop[3] ? crop[1] : qh / 3;
  const int box[4] = {cx, cy, crop[2], crop[3]};
  Buffer strip(box[2] * (kConfigCount + 1), box[3], 3), maps(qw * 2 * kConfigCount, qh, 3);
  paste(strip, cropOf(ref, box), 0);
  for (int c = 0; c < kConfigCount; ++c) {
    paste(strip, cropOf(images[size_t(c)], box), box[2] * (c + 1));
    Buffer map;
    flip(ref, images[size_t(c)], &map);
    paste(maps, flipColorMap(map), qw * 2 * c);
  }
  writePng((fs::path(o.out) / ("figure17_" + label + ".png")).string(), strip);
  report.image("figure17_" + label + ".png",
               o.sceneLabels[s] + ": reference, " + configLabels(", ") + " (same crop, left eye)");
  writePng((fs::path(o.out) / ("figure18_" + label + ".png")).string(), maps);
  report.image("figure18_" + label + ".png",
               o.sceneLabels[s] + ": FLIP against the reference, " + configLabels(" | "));
}

// Table 5's rows of scene s: every configuration against the converged reference (and its
// images, for Figures 17 and 18); the differences to each Base go to `summary`.
void table5Scene(const FoveatedExperimentOptions& o, const Scene& scene, size_t s,
                 const FoveationMap& qm, std::vector<std::vector<std::string>>& t5,
                 std::string& summary, ExperimentReport& report) {
  const int qw = o.qualityWidth, qh = o.qualityHeight, kConfigCount = int(configs().size());
  std::printf("experiment foveated: Table 5, %s, reference (%d spp)\n", o.sceneLabels[s].c_str(),
              o.referenceSpp);
  std::fflush(stdout);
  const CameraDesc cam = defaultCamera(scene);
  const Buffer ref = convergedDualImage(scene, cam, qw, qh, o.referenceSpp, o.cache);
  const std::string label = sceneLabel(o.scenes[s]);
  writePng((fs::path(o.out) / ("reference_" + label + ".png")).string(), ref);
  report.image("reference_" + label + ".png",
               o.sceneLabels[s] + ": reference (" + std::to_string(o.referenceSpp) + " spp)");
  std::vector<Buffer> images;
  std::vector<double> ssims(size_t(kConfigCount), 0.0), foveas(size_t(kConfigCount), 0.0);
  for (int c = 0; c < kConfigCount; ++c) {
    const Config& cf = configs()[size_t(c)];
    Renderer rd = makeRenderer(scene, cf.pipeline, qw, qh, cf.sets);
    // The thesis' configurations from one frame; the accumulating one after temporalFrames
    // frames of the still camera.
    const int frames = cf.temporal ? o.temporalFrames : 1;
    for (int f = 0; f < frames; ++f) rd.renderFrame(0, cam);
    const Buffer img = rd.output();
    images.push_back(img);
    Buffer ssimMap;
    const ImageMetrics m = compareImages(img, ref, &ssimMap);
    const Buffer err = squaredError(img, ref);
    const double fovea = meanOverLayer(ssimMap, qm, 0), periphery = meanOverLayer(ssimMap, qm, 2);
    ssims[size_t(c)] = m.ssim;
    foveas[size_t(c)] = fovea;
    const int b = cf.base;
    t5.push_back({o.sceneLabels[s], cf.label, fmt(100.0 * m.rmse, 4), fmt(m.ssim, 6),
                  fmt(m.psnr, 4), fmt(fovea, 4),
                  fmt(100.0 * std::sqrt(meanOverLayer(err, qm, 0)), 3), fmt(periphery, 4),
                  fmt(100.0 * std::sqrt(meanOverLayer(err, qm, 2)), 3), fmt(flip(ref, img), 4)});
    if (c >= 2 && b != c)
      summary += "- " + o.sceneLabels[s] + ": " + cf.label + " SSIM − " +
                 configs()[size_t(b)].label + " = " + fmt(m.ssim - ssims[size_t(b)], 4) +
                 " (fovea " + fmt(fovea - foveas[size_t(b)], 4) + ")\n";
    const std::string file = "image_" + label + "_" + cf.file + ".png";
    writePng((fs::path(o.out) / file).string(), img);
    report.image(file, o.sceneLabels[s] + ": " + cf.label);
  }
  figures17And18(o, s, ref, images, report);
}

// Table 5 and Figures 17-18: quality at the quality size against the converged reference.
std::string table5(const FoveatedExperimentOptions& o, const std::vector<Scene>& scenes,
                   ExperimentReport& report) {
  std::string summary;
  const int qw = o.qualityWidth, qh = o.qualityHeight;
  std::vector<std::vector<std::string>> t5;
  const FoveationDesc qd = scaledLayers(qh);
  const FoveationMap qm = computeFoveation(qw, qh, qd);
  for (size_t s = 0; s < scenes.size(); ++s) table5Scene(o, scenes[s], s, qm, t5, summary, report);
  report.markdown("### Table 5 shape: quality against the same path tracer converged (" +
                  std::to_string(o.referenceSpp) + " spp, no foveation, no denoising), " +
                  std::to_string(qw) + "x" + std::to_string(qh) + " per eye (radii " +
                  fmt(qd.r0, 0) + " / " + fmt(qd.r1, 0) +
                  "); fovea = inner layer, periphery = outer layer, both eyes\n\n");
  report.table("table5_quality",
               {"scene", "renderer", "RMSE (%)", "SSIM", "PSNR (dB)", "fovea SSIM",
                "fovea RMSE (%)", "periphery SSIM", "periphery RMSE (%)", "FLIP"},
               t5);
  return summary;
}

// Moving camera: the accumulating configuration is fair only if it also holds up while the
// camera moves; the first temporalFrames frames of each path at 30 fps, the last one measured.
void movingCamera(const FoveatedExperimentOptions& o, const std::vector<Scene>& scenes,
                  ExperimentReport& report) {
  const int kConfigCount = int(configs().size());
  std::vector<std::vector<std::string>> moving;
  std::vector<std::pair<std::string, std::string>> movingImages;  // file, caption
  std::string movingSummary;
  const int pw = o.pathWidth, ph = o.pathHeight;
  const FoveationMap pm = computeFoveation(pw, ph, scaledLayers(ph));
  for (size_t s = 0; s < scenes.size() && o.pathReferenceSpp > 0; ++s) {
    std::printf("experiment foveated: moving camera, %s\n", o.sceneLabels[s].c_str());
    std::fflush(stdout);
    const CameraDesc base = defaultCamera(scenes[s]);
    const int last = o.temporalFrames - 1;
    const CameraDesc lastCam = pathCameraAt(scenes[s], base, float(last) / 30.0f);
    const Buffer ref = convergedDualImage(scenes[s], lastCam, pw, ph, o.pathReferenceSpp, o.cache);
    // The left eyes side by side: the reference, then each configuration measured.
    const int leftEye[4] = {0, 0, pw, ph};
    std::vector<Buffer> eyes = {cropOf(ref, leftEye)};
    std::string caption = "reference";
    double baseSsim = 0, baseFovea = 0;
    for (int c = 0; c < kConfigCount; ++c) {
      // Base, NH3LD and the accumulating configurations (the others change the filter or the
      // light choice, not what a moving camera does to history).
      if (!configs()[size_t(c)].moving && !configs()[size_t(c)].temporal) continue;
      const Config& cf = configs()[size_t(c)];
      Renderer rd = makeRenderer(scenes[s], cf.pipeline, pw, ph, cf.sets);
      for (int f = 0; f <= last; ++f)
        rd.renderFrame(f, pathCameraAt(scenes[s], base, float(f) / 30.0f));
      Buffer ssimMap;
      const ImageMetrics m = compareImages(rd.output(), ref, &ssimMap);
      const double fovea = meanOverLayer(ssimMap, pm, 0);
      if (c == 0) baseSsim = m.ssim, baseFovea = fovea;
      if (c != 0)
        movingSummary += "- " + o.sceneLabels[s] + ", moving: " + cf.label +
                         " SSIM − Base = " + fmt(m.ssim - baseSsim, 4) + " (fovea " +
                         fmt(fovea - baseFovea, 4) + ")\n";
      moving.push_back({o.sceneLabels[s], cf.label, fmt(m.ssim, 4), fmt(fovea, 4),
                        fmt(meanOverLayer(ssimMap, pm, 2), 4), fmt(100.0 * m.rmse, 3)});
      eyes.push_back(cropOf(rd.output(), leftEye));
      caption += std::string(", ") + cf.label;
    }
    Buffer strip(pw * int(eyes.size()), ph, 3);
    for (size_t i = 0; i < eyes.size(); ++i) paste(strip, eyes[i], int(i) * pw);
    const std::string file = "moving_" + sceneLabel(o.scenes[s]) + ".png";
    writePng((fs::path(o.out) / file).string(), strip);
    movingImages.push_back({file, o.sceneLabels[s] + ", frame " + std::to_string(o.temporalFrames) +
                                      " of the path (left eye): " + caption});
  }
  if (!moving.empty()) {
    report.markdown("### Moving camera: frame " + std::to_string(o.temporalFrames) +
                    " of each camera path at 30 fps, " + std::to_string(pw) + "x" +
                    std::to_string(ph) + " per eye, against its own reference (" +
                    std::to_string(o.pathReferenceSpp) + " spp)\n\n");
    report.table("moving_camera_quality",
                 {"scene", "renderer", "SSIM", "fovea SSIM", "periphery SSIM", "RMSE (%)"}, moving);
    report.markdown(movingSummary + "\n");
    for (const auto& [file, caption] : movingImages) report.image(file, caption);
  }
}

}  // namespace

int runFoveatedExperiment(const FoveatedExperimentOptions& o) {
  std::vector<Scene> scenes;
  for (const std::string& s : o.scenes) scenes.push_back(loadScene(s));
  for (const Config& c : configs()) Pipeline::load(c.pipeline);
  fs::create_directories(o.out);
  ExperimentReport report(o.out,
                          "Peres 2022: foveated stereo path tracing, non-homogeneous denoising");
  table2(o, report);
  const std::vector<double> speedups = table4(o, scenes, report);
  const std::string summary = table5(o, scenes, report);
  movingCamera(o, scenes, report);
  const int qw = o.qualityWidth, qh = o.qualityHeight;
  report.markdown("The NH3LD + temporal rows (beyond the thesis) are measured after " +
                  std::to_string(o.temporalFrames) +
                  " frames of the still camera (its periphery averages them); the others from "
                  "one frame.\n\n");
  std::string sp = "- NH3LD speed-up over Base:";
  for (double v : speedups) sp += " " + fmt(v, 2);
  report.markdown(sp + " (per resolution and scene, in Table 4's order)\n" + summary + "\n");
  char settings[256];
  std::snprintf(settings, sizeof settings,
                "timings: %d untimed + %d (fhd) / %d (quest2) frames along each camera path; "
                "quality %dx%d per eye, reference %d spp, temporal %d frames",
                o.warmup, o.fhdFrames, o.quest2Frames, qw, qh, o.referenceSpp, o.temporalFrames);
  report.write(settings);
  return 0;
}

}  // namespace tandem
