#include "eval/experiments/experiment_interleaved.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <utility>

#include "core/image_io.h"
#include "core/json_fields.h"
#include "eval/experiments/experiment_report.h"
#include "eval/metrics/flip.h"
#include "eval/metrics/metrics.h"
#include "eval/reference/reference_cache.h"
#include "passes/baselines/accumulation.h"
#include "passes/baselines/taa.h"
#include "passes/interleaved/interleaved_raster.h"
#include "passes/interleaved/postfx_motion_blur.h"
#include "pipeline/aov.h"
#include "pipeline/pass_edit.h"
#include "pipeline/pass_times.h"
#include "pipeline/renderer.h"
#include "raster/sample_layout.h"
#include "raster/sample_tiles.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {

namespace fs = std::filesystem;

InterleavedExperimentOptions interleavedOptionsFromJson(const nlohmann::json& j,
                                                        const std::string& file) {
  JsonFields f(j, file, "");
  InterleavedExperimentOptions o;
  f.string("title", "");
  f.string("description", "");
  f.string("runner", "interleaved");
  scenePairsFromJson(f, o.sceneLabels, o.scenes);
  auto intList = [&](const char* key, std::vector<int>& out, int lo, int hi) {
    if (!f.has(key)) return;
    const Json& a = f.raw(key);
    if (!a.is_array() || a.empty()) f.fail(key, "expected a non-empty array of integers");
    out.clear();
    for (const Json& v : a) {
      if (!v.is_number_integer() || v.get<int>() < lo || v.get<int>() > hi)
        f.fail(key,
               "expected integers in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      out.push_back(v.get<int>());
    }
  };
  o.shutter = f.number("shutter", o.shutter, 0.0f, 1000.0f);
  o.width = f.integer("width", o.width, 8, 16384);
  o.height = f.integer("height", o.height, 8, 16384);
  o.referenceSpp = f.integer("referenceSpp", o.referenceSpp, 1, 1 << 20);
  o.seeds = f.integer("seeds", o.seeds, 1, 1000);
  intList("pairCounts", o.pairCounts, 1, 4096);
  o.sweepSpp = f.integer("sweepSpp", o.sweepSpp, 1, 64);
  intList("sppCounts", o.sppCounts, 1, 64);
  o.sweepPairs = f.integer("sweepPairs", o.sweepPairs, 1, 4096);
  o.timingWidth = f.integer("timingWidth", o.timingWidth, 8, 16384);
  o.timingHeight = f.integer("timingHeight", o.timingHeight, 8, 16384);
  o.timingFrames = f.integer("timingFrames", o.timingFrames, 1, 10000);
  o.timingWarmup = f.integer("timingWarmup", o.timingWarmup, 0, 10000);
  o.timingPairs = f.integer("timingPairs", o.timingPairs, 1, 4096);
  o.timingSpp = f.integer("timingSpp", o.timingSpp, 1, 64);
  o.strobePairs = f.integer("strobePairs", o.strobePairs, 1, 4096);
  o.sequenceFrames = f.integer("sequenceFrames", o.sequenceFrames, 2, 10000);
  cropFromJson(f, o.crop);
  f.finish();
  // Every (N, k) the runs use must make a tile.
  auto check = [&](int n, int k, const char* what) {
    const std::string p = tileShapeProblem(n, k);
    if (!p.empty()) throw InputError(file, what, p);
  };
  for (int n : o.pairCounts) check(n, o.sweepSpp, "pairCounts / sweepSpp");
  for (int k : o.sppCounts) check(o.sweepPairs, k, "sweepPairs / sppCounts");
  check(o.timingPairs, o.timingSpp, "timingPairs / timingSpp");
  check(o.strobePairs, 1, "strobePairs");
  return o;
}

namespace {

// The sampling schemes compared, with their names (as interleaved_raster.scheme spells them).
const std::pair<const char*, SamplingScheme> kSchemes[] = {
    {"independent", SamplingScheme::Independent},
    {"stratified", SamplingScheme::Stratified},
    {"random_tiles", SamplingScheme::RandomTiles},
    {"colored_corner", SamplingScheme::ColoredCorner}};
using Mode = InterleavedSettings::Mode;
using Shading = InterleavedSettings::Shading;

// The accumulation baseline's mode for the interleaved passes' one.
AccumulationSettings::Mode accumulationMode(Mode m) {
  return m == Mode::Dof          ? AccumulationSettings::Mode::Dof
         : m == Mode::MotionBlur ? AccumulationSettings::Mode::MotionBlur
                                 : AccumulationSettings::Mode::Both;
}

// A scene's shot at time 0: the camera at shutter open and close (its path), and what the
// pairs vary (the lens only where the camera has an aperture; time only where something moves).
struct Shot {
  Scene scene;
  CameraDesc base, open, close;  // base: the scene's camera; open, close: on its path at time 0
  std::string label;
  Mode mode = Mode::Both;  // what the pairs vary
};

Shot shotOf(const std::string& spec, const std::string& label, float shutter) {
  Shot s{loadScene(spec), {}, {}, {}, label};
  const CameraDesc base = defaultCamera(s.scene);
  s.base = base;
  s.open = pathCameraAt(s.scene, base, 0.0f);
  s.close = pathCameraAt(s.scene, base, shutter);
  bool moves =
      length(s.open.position - s.close.position) > 0 || length(s.open.lookAt - s.close.lookAt) > 0;
  for (const Object& o : s.scene.objects) moves = moves || o.animation.size() > 1;
  const bool lens = s.open.apertureDiameter > 0;
  s.mode = lens && moves ? Mode::Both : lens ? Mode::Dof : Mode::MotionBlur;
  return s;
}

struct RenderResult {
  Buffer hdr;
  double frameMs = 0;
  std::map<std::string, double> partMs;  // median ms per pass type and "type/part"
  std::map<std::string, double> counters;
};

RenderResult renderShot(const Shot& shot, const std::string& pipeline, const PipelineEdits& edits,
                        int w, int h, float shutter, uint64_t seed, int warmup = 0, int frames = 1,
                        float frameStep = 0.0f) {
  Pipeline p = Pipeline::load(pipeline);
  applyEdits(p, edits);
  Renderer r(shot.scene, std::move(p),
             RenderSettings{.width = w, .height = h, .seed = seed, .shutter = shutter});
  r.keepOnDevice();  // timed: nothing read back until the frames are done
  std::vector<double> total;
  std::map<std::string, std::vector<double>> parts;
  for (int f = 0; f < warmup + frames; ++f) {
    // frameStep 0: every frame the same instant (time 0); otherwise a sequence from time 0.
    const float time = float(f) * frameStep;
    const FrameTimings t =
        frameStep > 0 ? r.renderFrameAt(f, time, pathCameraAt(shot.scene, shot.base, time),
                                        pathCameraAt(shot.scene, shot.base, time + shutter))
                      : r.renderFrameAt(0, 0.0f, shot.open, shot.close);
    if (f < warmup) continue;
    total.push_back(t.totalMs);
    for (const PassTiming& pt : t.passes) parts[pt.name].push_back(pt.ms);
  }
  RenderResult out;
  out.hdr = r.fetch("hdr");
  out.frameMs = summarize(total).median;
  std::map<std::string, double> medians;
  for (auto& [name, v] : parts) medians[name] = summarize(v).median;
  out.partMs = PassTimes(r.pipeline(), std::move(medians)).byType();
  out.counters = r.context().counters;
  return out;
}

Buffer referenceOf(const Shot& shot, int w, int h, float shutter, int spp, const std::string& cache,
                   float time = 0.0f) {
  ReferenceJob job;
  job.scene = &shot.scene;
  job.camera = pathCameraAt(shot.scene, shot.base, time);
  job.shutterCamera = pathCameraAt(shot.scene, shot.base, time + shutter);
  job.time = time;
  job.shutter = shutter;
  job.width = w;
  job.height = h;
  job.settings.spp = spp;
  job.settings.integrator = Integrator::Whitted;
  job.settings.progress = true;
  return referenceImage(job, cache).hdr;
}

struct Errors {
  double rmse = 0, ssim = 0, flip = 0;
};

Errors errorsOf(const Buffer& img, const Buffer& ref) {
  const Buffer a = visualizeBuffer(img), b = visualizeBuffer(ref);
  return {tandem::rmse(img, ref), tandem::ssim(a, b), tandem::flip(b, a)};
}

std::string pixelsLabel(int n, int k) {
  return "N " + std::to_string(n) + ", k " + std::to_string(k);
}

// Tile quality: the colored-corner tiles against random tiles, N x k.
void tileQualityTable(ExperimentReport& report) {
  std::vector<std::vector<std::string>> rows;
  for (int n : {4, 8, 16, 32, 64})
    for (int k : {1, 4}) {
      if (!tileShapeProblem(n, k).empty()) continue;
      const std::vector<TimeLensPair> pairs = stratifiedTimeLensPairs(n, 1);
      for (TileKind kind : {TileKind::Random, TileKind::ColoredCorner}) {
        const auto t0 = std::chrono::steady_clock::now();
        const TileSet set = buildTileSet(n, k, kind, PairMetric::Time, pairs, 1);
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        const TileQuality& q = set.quality;
        rows.push_back({std::to_string(n), std::to_string(k),
                        std::to_string(set.shape.tw) + "x" + std::to_string(set.shape.th),
                        kind == TileKind::Random ? "random" : "colored corner",
                        fmt(q.minSimilarTimeDistance, 3), fmt(q.meanSimilarTimeDistance, 3),
                        fmt(q.meanFootprintDiscrepancy, 3), fmt(q.maxFootprintDiscrepancy, 3),
                        fmt(ms, 1)});
      }
    }
  report.markdown(
      "### Tile quality (time metric, seed 1)\n\nSimilar times: equal or adjacent in T's time "
      "order; distances between stratum centres over 12 x 12 tiles, in pixels. Discrepancy: "
      "star discrepancy of the times in each 2 x 2-pixel footprint. Build: ms to generate all "
      "81 prototypes (and measure them).\n\n");
  report.table(
      "tile_quality",
      {"N", "k", "tile (px)", "tiles", "min similar-time distance", "mean similar-time distance",
       "mean footprint discrepancy", "worst footprint discrepancy", "build ms"},
      rows);
}

// The same-shading references (distributed ray tracing of the Whitted shading).
std::vector<Buffer> references(const InterleavedExperimentOptions& o,
                               const std::vector<Shot>& shots, ExperimentReport& report) {
  const int W = o.width, H = o.height;
  std::vector<Buffer> refs;
  for (const Shot& s : shots) {
    std::printf("experiment interleaved: reference %s (%d spp, whitted)\n", s.label.c_str(),
                o.referenceSpp);
    std::fflush(stdout);
    refs.push_back(referenceOf(s, W, H, o.shutter, o.referenceSpp, o.cache));
    writePng((fs::path(o.out) / ("reference_" + s.label + ".png")).string(),
             visualizeBuffer(refs.back()));
    report.image("reference_" + s.label + ".png",
                 s.label + ": reference (whitted, " + std::to_string(o.referenceSpp) + " spp)");
  }
  return refs;
}

// Mean errors over the seeds of one configuration.
Errors measure(const InterleavedExperimentOptions& o, const Shot& shot, const Buffer& ref,
               const std::string& pipeline, const PipelineEdits& edits) {
  Errors e;
  for (int seed = 0; seed < o.seeds; ++seed) {
    const RenderResult r =
        renderShot(shot, pipeline, edits, o.width, o.height, o.shutter, uint64_t(seed));
    const Errors x = errorsOf(r.hdr, ref);
    e.rmse += x.rmse / o.seeds;
    e.ssim += x.ssim / o.seeds;
    e.flip += x.flip / o.seeds;
  }
  return e;
}

PipelineEdits interleavedSets(const Shot& s, int n, int k, SamplingScheme scheme) {
  return {editPass<InterleavedRasterPass>([=, mode = s.mode](InterleavedSettings& i) {
    i.samples = n;
    i.spp = k;
    i.scheme = scheme;
    i.mode = mode;
    i.filter = InterleavedSettings::Filter::Box;
    i.filterRadius = 0.5f;
  })};
}

// The brute-force baseline: n whole images averaged, Whitted-shaded.
PipelineEdits accumulationSets(const Shot& s, int n) {
  return {editPass<AccumulationPass>([=, mode = s.mode](AccumulationSettings& a) {
    a.samples = n;
    a.mode = accumulationMode(mode);
    a.shading = AccumulationSettings::Shading::Whitted;
  })};
}

// One scene's errors against N (each scheme, and accumulation) and against k, with their plots;
// adds to the tables' rows and to the figure check.
void errorSweeps(const InterleavedExperimentOptions& o, const Shot& s, const Buffer& ref,
                 ExperimentReport& report, std::vector<std::vector<std::string>>& nRows,
                 std::vector<std::vector<std::string>>& kRows, std::string& figureCheck) {
  std::vector<PlotSeries> rmsePlot, ssimPlot;
  std::map<std::string, std::vector<double>> rmseOf;
  for (const auto& [scheme, layout] : kSchemes) {
    PlotSeries pr{scheme, {}, {}}, ps{scheme, {}, {}};
    for (int n : o.pairCounts) {
      std::printf("experiment interleaved: %s, %s, N %d, k %d\n", s.label.c_str(), scheme, n,
                  o.sweepSpp);
      std::fflush(stdout);
      const Errors e =
          measure(o, s, ref, "interleaved-raster", interleavedSets(s, n, o.sweepSpp, layout));
      nRows.push_back({s.label, scheme, std::to_string(n), std::to_string(o.sweepSpp),
                       fmt(e.rmse, 4), fmt(e.ssim, 4), fmt(e.flip, 4)});
      pr.x.push_back(n);
      pr.y.push_back(e.rmse);
      ps.x.push_back(n);
      ps.y.push_back(e.ssim);
      rmseOf[scheme].push_back(e.rmse);
    }
    rmsePlot.push_back(pr);
    ssimPlot.push_back(ps);
  }
  // The brute-force baseline: N whole images averaged (N samples per pixel).
  {
    PlotSeries pr{"accumulation (N images)", {}, {}}, ps{"accumulation (N images)", {}, {}};
    for (int n : o.pairCounts) {
      std::printf("experiment interleaved: %s, accumulation, N %d\n", s.label.c_str(), n);
      std::fflush(stdout);
      const Errors e = measure(o, s, ref, "accumulation-dof", accumulationSets(s, n));
      nRows.push_back({s.label, "accumulation (N images, N spp)", std::to_string(n), "-",
                       fmt(e.rmse, 4), fmt(e.ssim, 4), fmt(e.flip, 4)});
      pr.x.push_back(n);
      pr.y.push_back(e.rmse);
      ps.x.push_back(n);
      ps.y.push_back(e.ssim);
    }
    rmsePlot.push_back(pr);
    ssimPlot.push_back(ps);
  }
  report.plot("rmse_vs_n_" + s.label,
              s.label + ": RMSE against N (k = " + std::to_string(o.sweepSpp) + ")",
              "N (time, lens) pairs", "RMSE", rmsePlot, true, true);
  report.plot("ssim_vs_n_" + s.label,
              s.label + ": SSIM against N (k = " + std::to_string(o.sweepSpp) + ")",
              "N (time, lens) pairs", "SSIM", ssimPlot, true);
  // The figure: colored-corner below random tiles at every N >= 8.
  int wins = 0, points = 0;
  for (size_t i = 0; i < o.pairCounts.size(); ++i) {
    if (o.pairCounts[i] < 8) continue;
    ++points;
    wins += rmseOf["colored_corner"][i] < rmseOf["random_tiles"][i];
  }
  figureCheck += "- " + s.label + ": colored-corner RMSE below random tiles at " +
                 std::to_string(wins) + " of " + std::to_string(points) + " N >= 8\n";

  std::vector<PlotSeries> kPlot;
  for (const auto& [scheme, layout] : kSchemes) {
    PlotSeries pk{scheme, {}, {}};
    for (int k : o.sppCounts) {
      std::printf("experiment interleaved: %s, %s, N %d, k %d\n", s.label.c_str(), scheme,
                  o.sweepPairs, k);
      std::fflush(stdout);
      const Errors e =
          measure(o, s, ref, "interleaved-raster", interleavedSets(s, o.sweepPairs, k, layout));
      kRows.push_back({s.label, scheme, std::to_string(o.sweepPairs), std::to_string(k),
                       fmt(e.rmse, 4), fmt(e.ssim, 4), fmt(e.flip, 4)});
      pk.x.push_back(k);
      pk.y.push_back(e.rmse);
    }
    kPlot.push_back(pk);
  }
  report.plot(
      "rmse_vs_k_" + s.label,
      s.label + ": RMSE against samples per pixel (N = " + std::to_string(o.sweepPairs) + ")",
      "k samples per pixel", "RMSE", kPlot, true, true);
}

// Error against N and against samples per pixel, against the same-shading reference.
void errorTables(const InterleavedExperimentOptions& o, const std::vector<Shot>& shots,
                 const std::vector<Buffer>& refs, ExperimentReport& report) {
  const int W = o.width, H = o.height;
  std::vector<std::vector<std::string>> nRows, kRows;
  std::string figureCheck;
  for (size_t si = 0; si < shots.size(); ++si)
    errorSweeps(o, shots[si], refs[si], report, nRows, kRows, figureCheck);
  const std::string schemeNote =
      "Interleaved rasterization (`interleaved-raster`, its pass's `mode` set to what the scene "
      "varies, a pixel box filter as the reference's) at " +
      std::to_string(W) + "x" + std::to_string(H) + ", mean of " + std::to_string(o.seeds) +
      " frames (seeds: new T, new tiles), against the same-shading reference (distributed ray "
      "tracing of the Whitted shading at the same shutter and aperture). Schemes: independent "
      "(a random pair of T per sample), stratified (a pixel's k samples from k time strata of T), "
      "random tiles (81 random permutations), colored corner (81 optimised tiles); accumulation: "
      "N whole rasterized images averaged (N samples per pixel), shaded the same way.\n\n";
  report.markdown("### Error against N\n\n" + schemeNote);
  report.table("error_vs_n", {"scene", "scheme", "N", "k", "RMSE", "SSIM", "FLIP"}, nRows);
  report.markdown("Figure check:\n\n" + figureCheck + "\n");
  report.markdown("### Error against samples per pixel\n\n" + schemeNote);
  report.table("error_vs_k", {"scene", "scheme", "N", "k", "RMSE", "SSIM", "FLIP"}, kRows);
}

// Time per frame at equal samples: rasterized against ray-traced visibility, and brute force.
void timePerFrameTable(const InterleavedExperimentOptions& o, const std::vector<Shot>& shots,
                       ExperimentReport& report) {
  std::vector<std::vector<std::string>> rows;
  std::string ratios;
  const int n = o.timingPairs, k = o.timingSpp, tw = o.timingWidth, th = o.timingHeight;
  for (const Shot& s : shots) {
    for (const auto& [shading, how] :
         {std::pair{"whitted", Shading::Whitted}, std::pair{"local", Shading::Local}}) {
      double rasterMs = 0, rasterVis = 0;
      for (const char* pass : {"interleaved_raster", "interleaved_rt"}) {
        std::printf("experiment interleaved: timing %s, %s, %s\n", s.label.c_str(), pass, shading);
        std::fflush(stdout);
        const std::string pl =
            std::string(pass) == "interleaved_rt" ? "interleaved-rt" : "interleaved-raster";
        const std::string P = pass;
        const PipelineEdit edit =
            editPass<InterleavedPass>(P, [&, how = how](InterleavedSettings& i) {
              i.samples = n;
              i.spp = k;
              i.mode = s.mode;
              i.shading = how;
            });
        const RenderResult r =
            renderShot(s, pl, {edit}, tw, th, o.shutter, 0, o.timingWarmup, o.timingFrames);
        const double vis = r.partMs.count(P + "/visibility") ? r.partMs.at(P + "/visibility") : 0;
        const double shade = r.partMs.count(P + "/shade") ? r.partMs.at(P + "/shade") : 0;
        const double resolve = r.partMs.count(P + "/resolve") ? r.partMs.at(P + "/resolve") : 0;
        const auto c = r.counters.find(InterleavedRasterCounters::setUpPerPass);
        rows.push_back({s.label, pl, shading, pixelsLabel(n, k), fmt(r.frameMs, 1), fmt(vis, 1),
                        fmt(shade, 1), fmt(resolve, 1),
                        c != r.counters.end() ? fmt(c->second, 0) : "-"});
        if (P == "interleaved_raster") {
          rasterMs = r.frameMs;
          rasterVis = vis;
        } else {
          ratios += "- " + s.label + ", " + shading + " shading: ray tracing / rasterization " +
                    fmt(r.frameMs / rasterMs, 2) + "x per frame, " + fmt(vis / rasterVis, 2) +
                    "x for visibility\n";
        }
      }
    }
    std::printf("experiment interleaved: timing %s, accumulation\n", s.label.c_str());
    std::fflush(stdout);
    const RenderResult a = renderShot(s, "accumulation-dof", accumulationSets(s, n), tw, th,
                                      o.shutter, 0, o.timingWarmup, o.timingFrames);
    rows.push_back({s.label, "accumulation (brute force)", "whitted",
                    std::to_string(n) + " images, " + std::to_string(n) + " spp", fmt(a.frameMs, 1),
                    "-", "-", "-", "-"});
  }
  report.markdown("### Time per frame at " + std::to_string(tw) + "x" + std::to_string(th) +
                  " (median of " + std::to_string(o.timingFrames) +
                  " frames)\n\nVisibility: the part the two variants differ in (rasterization "
                  "per pair of T against primary rays); shading and resolve are the same code. "
                  "Triangles: set up per pass of the rasterizer (moving objects only when no "
                  "pair moves the camera: the still geometry is rasterized once).\n\n");
  report.table("time_per_frame",
               {"scene", "pipeline", "shading", "samples", "frame ms", "visibility ms", "shade ms",
                "resolve ms", "triangles per pass"},
               rows);
  report.markdown(ratios + "\n");
}

// Strobing at small N: decorrelated against correlated pairs, against the reference.
void strobingTable(const InterleavedExperimentOptions& o, const std::vector<Shot>& shots,
                   const std::vector<Buffer>& refs, ExperimentReport& report) {
  const int W = o.width, H = o.height;
  std::vector<std::vector<std::string>> rows;
  const size_t si = shots.size() - 1;  // the scene with both effects
  const Shot& s = shots[si];
  const int n = o.strobePairs;
  struct Variant {
    std::string name, pipeline;
    PipelineEdits sets;
  };
  const std::string N = std::to_string(n);
  const auto tiles = [&](bool correlated) {
    return editPass<InterleavedRasterPass>([=, mode = s.mode](InterleavedSettings& i) {
      i.samples = n;
      i.spp = 1;
      i.mode = mode;
      i.correlated = correlated;
    });
  };
  const std::vector<Variant> variants = {
      {"colored_corner", "interleaved-raster", {tiles(false)}},
      {"colored_corner_correlated", "interleaved-raster", {tiles(true)}},
      {"accumulation", "accumulation-dof", accumulationSets(s, n)}};
  const Buffer refCrop = cropOf(visualizeBuffer(refs[si]), o.crop);
  writePng((fs::path(o.out) / "strobe_reference.png").string(), refCrop);
  report.image("strobe_reference.png", s.label + ": reference (crop)");
  for (const Variant& v : variants) {
    const RenderResult r = renderShot(s, v.pipeline, v.sets, W, H, o.shutter, 0);
    const Errors e = errorsOf(r.hdr, refs[si]);
    rows.push_back({v.name, N, fmt(e.rmse, 4), fmt(e.ssim, 4), fmt(e.flip, 4)});
    const std::string file = "strobe_" + v.name + ".png";
    writePng((fs::path(o.out) / file).string(), cropOf(visualizeBuffer(r.hdr), o.crop));
    report.image(file, s.label + ": " + v.name + ", N = " + N + " (crop)");
  }
  report.markdown("### Strobing at N = " + N + " (" + s.label +
                  ")\n\nCorrelated: the i-th time with the i-th lens point (the compromise of "
                  "interval methods); decorrelated: a seeded permutation between them.\n\n");
  report.table("strobing", {"variant", "N", "RMSE", "SSIM", "FLIP"}, rows);
}

// Hybrid motion blur (Tan et al. 2022's future work) against post-process only and full interleaved
// sampling, on every scene without depth of field.
void hybridMotionBlurTable(const InterleavedExperimentOptions& o, const std::vector<Shot>& shots,
                           ExperimentReport& report) {
  std::vector<std::vector<std::string>> rows;
  std::string check;
  for (size_t si = 0; si < shots.size(); ++si) {
    const Shot& s = shots[si];
    if (s.mode != Mode::MotionBlur) continue;
    // The two the summary compares: the hybrid as shipped, and full interleaved sampling at k 4.
    enum class Role { Other, Hybrid, Full };
    struct Variant {
      std::string name, pipeline;
      PipelineEdits sets;
      Role role = Role::Other;
    };
    const auto motionBlur = [](int k) {
      return editPass<InterleavedRasterPass>([=](InterleavedSettings& i) {
        i.mode = Mode::MotionBlur;
        i.spp = k;
      });
    };
    const std::vector<Variant> variants = {
        {"postfx only", "postfx-motion-blur", {}},
        {"hybrid", "hybrid-motion-blur", {}, Role::Hybrid},
        {"hybrid, 4-spp sharp image, no TAA",
         "hybrid-motion-blur",
         {editPass<InterleavedRasterPass>("sharp",
                                          [](InterleavedSettings& i) {
                                            i.samples = 4;
                                            i.spp = 4;
                                            i.shadingRate = InterleavedSettings::ShadingRate::Pixel;
                                            i.viewJitter = false;
                                          }),
          editPass<TAAPass>("taa_sharp",
                            [](TAASettings& t) {
                              t.alpha = 1;
                              t.motionAlpha = 1;
                            })}},
        {"interleaved N 16, k 4", "interleaved-raster", {motionBlur(4)}, Role::Full},
        {"interleaved N 16, k 2", "interleaved-raster", {motionBlur(2)}},
        {"interleaved N 16, k 1", "interleaved-raster", {motionBlur(1)}}};
    double fullMs = 0, fullSsim = 0, hybridMs = 0, hybridSsim = 0;
    // A moving sequence: the temporal passes see the motion they would in use, and every
    // renderer pays its per-frame scene update. Errors on its last frame.
    const float step = 1.0f / 30.0f, lastTime = float(o.sequenceFrames - 1) * step;
    std::printf("experiment interleaved: reference %s at %dx%d, time %.3f s\n", s.label.c_str(),
                o.timingWidth, o.timingHeight, double(lastTime));
    std::fflush(stdout);
    const Buffer ref =
        referenceOf(s, o.timingWidth, o.timingHeight, o.shutter, o.referenceSpp, o.cache, lastTime);
    const std::string refFile = "mb_" + s.label + "_reference.png";
    writePng((fs::path(o.out) / refFile).string(), visualizeBuffer(ref));
    report.image(refFile, s.label + ": reference at " + fmt(lastTime, 3) + " s");
    for (const Variant& v : variants) {
      std::printf("experiment interleaved: hybrid motion blur, %s, %s\n", s.label.c_str(),
                  v.name.c_str());
      std::fflush(stdout);
      // Time and error on the same frames, at the timing size: the first seed timed.
      Errors e;
      RenderResult q, t;
      for (int seed = 0; seed < o.seeds; ++seed) {
        q = renderShot(s, v.pipeline, v.sets, o.timingWidth, o.timingHeight, o.shutter,
                       uint64_t(seed), 1, o.sequenceFrames - 1, step);
        if (seed == 0) t = q;
        const Errors x = errorsOf(q.hdr, ref);
        e.rmse += x.rmse / o.seeds;
        e.ssim += x.ssim / o.seeds;
        e.flip += x.flip / o.seeds;
      }
      const auto m = q.counters.find(PostfxMotionBlurCounters::maskedTilesPercent);
      rows.push_back({s.label, v.name, fmt(t.frameMs, 1), fmt(e.rmse, 4), fmt(e.ssim, 4),
                      fmt(e.flip, 4), m != q.counters.end() ? fmt(m->second, 1) : "-"});
      const std::string file =
          "mb_" + s.label + "_" + v.pipeline + "_" + std::to_string(rows.size()) + ".png";
      writePng((fs::path(o.out) / file).string(), visualizeBuffer(q.hdr));
      report.image(file, s.label + ": " + v.name);
      if (v.role == Role::Hybrid) hybridMs = t.frameMs, hybridSsim = e.ssim;
      if (v.role == Role::Full) fullMs = t.frameMs, fullSsim = e.ssim;
    }
    check += "- " + s.label + ": hybrid SSIM " + fmt(hybridSsim - fullSsim, 4) +
             " from full interleaved (N 16, k 4) at " + fmt(hybridMs / fullMs, 2) + "x its time\n";
  }
  report.markdown(
      "### Hybrid motion blur\n\nPost-process only: a sharp mid-shutter image (1 jittered "
      "sample per pixel, accumulated over frames by temporal AA as Tan et al. 2022 does; the same "
      "shading) blurred by McGuire et al.'s reconstruction filter (tile max velocity, gather). "
      "Hybrid: the same, with interleaved samples (N 16, k 4) inside the mask of tiles whose "
      "neighbourhood mixes motions, lerped by the mask; the row without TAA anti-aliases its "
      "sharp image with 4 samples per pixel shaded once per triangle seen (MSAA-style) instead. "
      "Interleaved: the whole image at k = 4, 2, 1. A moving sequence of " +
      std::to_string(o.sequenceFrames) + " frames 1/30 s apart from time 0 at " +
      std::to_string(o.timingWidth) + "x" + std::to_string(o.timingHeight) +
      " (time: median of its frames after the first, scene update included, first seed; "
      "errors: its last frame, mean of " +
      std::to_string(o.seeds) + " seeds, against a reference at that frame's time).\n\n");
  report.table("hybrid_motion_blur",
               {"scene", "renderer", "frame ms", "RMSE", "SSIM", "FLIP", "masked tiles %"}, rows);
  report.markdown(check + "\n");
}

}  // namespace

int runInterleavedExperiment(const InterleavedExperimentOptions& o) {
  std::vector<Shot> shots;
  for (size_t i = 0; i < o.scenes.size(); ++i)
    shots.push_back(shotOf(o.scenes[i], o.sceneLabels[i], o.shutter));
  fs::create_directories(o.out);
  ExperimentReport report(o.out,
                          "Foster 2015: interleaved sampling for depth of field and motion blur");
  tileQualityTable(report);
  const std::vector<Buffer> refs = references(o, shots, report);
  errorTables(o, shots, refs, report);
  timePerFrameTable(o, shots, report);
  strobingTable(o, shots, refs, report);
  hybridMotionBlurTable(o, shots, report);
  const int W = o.width, H = o.height;
  std::string settings = "size " + std::to_string(W) + "x" + std::to_string(H) + ", shutter " +
                         fmt(o.shutter, 3) + " s, reference " + std::to_string(o.referenceSpp) +
                         " spp (whitted), seeds " + std::to_string(o.seeds);
  report.write(settings);
  return 0;
}

}  // namespace tandem
