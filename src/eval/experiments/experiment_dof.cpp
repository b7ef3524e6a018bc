#include "eval/experiments/experiment_dof.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "core/image_io.h"
#include "core/json_fields.h"
#include "eval/experiments/experiment_report.h"
#include "eval/metrics/flip.h"
#include "eval/metrics/metrics.h"
#include "eval/reference/reference_cache.h"
#include "passes/dof/dof_accumulation.h"
#include "passes/dof/ray_mask.h"
#include "pipeline/aov.h"
#include "pipeline/pass_edit.h"
#include "pipeline/pass_times.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {

namespace fs = std::filesystem;

namespace {

std::vector<int> intList(JsonFields& f, const char* name, std::vector<int> def, int lo, int hi) {
  if (!f.has(name)) return def;
  const Json& a = f.raw(name);
  if (!a.is_array() || a.empty()) f.fail(name, "expected a non-empty array of integers");
  std::vector<int> out;
  for (const Json& v : a) {
    if (!v.is_number_integer() || v.get<int>() < lo || v.get<int>() > hi)
      f.fail(name, "expected integers in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    out.push_back(v.get<int>());
  }
  return out;
}

}  // namespace

DofExperimentOptions dofOptionsFromJson(const nlohmann::json& j, const std::string& file) {
  JsonFields f(j, file, "");
  DofExperimentOptions o;
  f.string("title", "");
  f.string("description", "");
  f.string("runner", "hybrid-dof");
  if (!f.has("shots") || !f.raw("shots").is_array() || f.raw("shots").empty())
    f.fail("shots", "expected an array of [label, scene] pairs");
  const fs::path base = fs::path(file).parent_path();
  for (const Json& shot : f.raw("shots")) {
    if (!shot.is_array() || shot.size() != 2 || !shot[0].is_string() || !shot[1].is_string())
      f.fail("shots", "each shot is [label, scene name or file]");
    std::string s = shot[1].get<std::string>();
    if (s.find('.') != std::string::npos && fs::path(s).is_relative()) s = (base / s).string();
    o.shotLabels.push_back(shot[0].get<std::string>());
    o.shots.push_back(s);
  }
  o.width = f.integer("width", o.width, 8, 16384);
  o.height = f.integer("height", o.height, 8, 16384);
  o.sweepWidth = f.integer("sweepWidth", o.sweepWidth, 8, 16384);
  o.sweepHeight = f.integer("sweepHeight", o.sweepHeight, 8, 16384);
  o.warmup = f.integer("warmup", o.warmup, 0, 100000);
  o.frames = f.integer("frames", o.frames, 1, 100000);
  o.tableWarmup = f.integer("tableWarmup", o.tableWarmup, 0, 100000);
  o.tableFrames = f.integer("tableFrames", o.tableFrames, 1, 100000);
  o.tableBudgets = intList(f, "tableBudgets", o.tableBudgets, 0, 1024);
  o.sweepBudgets = intList(f, "sweepBudgets", o.sweepBudgets, 0, 1024);
  if (f.has("figureShot")) {
    const std::string label = f.string("figureShot", "");
    o.figureShot = -2;
    for (size_t i = 0; i < o.shotLabels.size(); ++i)
      if (o.shotLabels[i] == label) o.figureShot = int(i);
    if (o.figureShot == -2) f.fail("figureShot", "'" + label + "' is not one of the shots");
  }
  o.referenceSpp = f.integer("referenceSpp", o.referenceSpp, 1, 1 << 20);
  o.pathReferenceSpp = f.integer("pathReferenceSpp", o.pathReferenceSpp, 1, 1 << 20);
  const std::vector<int> crop = intList(f, "crop", {0, 0, 0, 0}, 0, 16384);
  if (crop.size() != 4) f.fail("crop", "expected [x, y, width, height]");
  for (int k = 0; k < 4; ++k) o.crop[k] = crop[size_t(k)];
  o.temporalWidth = f.integer("temporalWidth", o.temporalWidth, 8, 16384);
  o.temporalHeight = f.integer("temporalHeight", o.temporalHeight, 8, 16384);
  o.temporalFrames = f.integer("temporalFrames", o.temporalFrames, 0, 100000);
  o.temporalEvery = f.integer("temporalEvery", o.temporalEvery, 1, 100000);
  o.temporalSpp = f.integer("temporalSpp", o.temporalSpp, 1, 1 << 20);
  f.finish();
  return o;
}

namespace {

struct StaticRun {
  Buffer image;                           // the displayed image after warm-up and the timed frames
  std::map<std::string, double> groupMs;  // median per Table 2 pass group (table2Group)
  double rtDofMs = 0;                     // median of the lens-ray pass (0 without one)
  double frameMs = 0;
  double raysPerPixel = 0, maskedShare = 0;
};

// Table 2's pass groups in its row order.
const std::vector<std::string>& table2Groups() {
  static const std::vector<std::string> g = {"sharp image (raster, RT shadows/reflections, TAA)",
                                             "post-process",
                                             "G-buffer & σ² blur (ray mask)",
                                             "ray trace",
                                             "accumulation",
                                             "median + reconstruction",
                                             "composite",
                                             "final TAA"};
  return g;
}

// The Table 2 group of a pass of `type` (empty: counted under "others"); a TAA pass is the sharp
// image's before the DoF composite and the final one after it.
std::string table2Group(const std::string& type, bool afterComposite) {
  static const std::map<std::string, size_t> byType = {{"raster_gbuffer", 0},
                                                       {"deferred_shading", 0},
                                                       {"heuristic", 0},
                                                       {"rt_secondary", 0},
                                                       {"blend", 0},
                                                       {"dof_coc", 1},
                                                       {"postfx_dof", 1},
                                                       {"ray_mask", 2},
                                                       {"rt_dof", 3},
                                                       {"dof_accumulation", 4},
                                                       {"dof_reconstruction", 5},
                                                       {"dof_composite", 6}};
  if (type == "taa") return table2Groups()[afterComposite ? 7 : 0];
  auto it = byType.find(type);
  return it == byType.end() ? std::string() : table2Groups()[it->second];
}

// Each group's ms, the pipeline's passes found by type (timing rows: medians by label).
std::map<std::string, double> groupTimes(const Pipeline& p, const PassTimes& times) {
  std::map<std::string, double> groups;
  bool afterComposite = false;
  for (size_t i = 0; i < p.passes.size(); ++i) {
    const std::string& type = p.passes[i]->type();
    const std::string g = table2Group(type, afterComposite);
    if (!g.empty()) groups[g] += times.ofPass(i);
    afterComposite |= type == "dof_composite";
  }
  return groups;
}

StaticRun renderStatic(const Scene& scene, const std::string& pipeline, const PipelineEdits& edits,
                       int w, int h, int warmup, int frames) {
  Pipeline p = Pipeline::load(pipeline);
  applyEdits(p, edits);
  Renderer r(scene, std::move(p), RenderSettings{.width = w, .height = h});
  r.keepOnDevice();  // timed: nothing read back until the frames are done
  const CameraDesc cam = defaultCamera(scene);
  for (int f = 0; f < warmup; ++f) r.renderFrame(0, cam);
  std::map<std::string, std::vector<double>> ms;
  std::vector<double> total;
  for (int f = 0; f < frames; ++f) {
    const FrameTimings ft = r.renderFrame(0, cam);
    for (const PassTiming& t : ft.passes) ms[t.name].push_back(t.ms);
    total.push_back(ft.totalMs);
  }
  StaticRun run;
  run.image = r.output();
  std::map<std::string, double> medians;
  for (auto& [name, v] : ms) medians[name] = summarize(v).median;
  const PassTimes times(r.pipeline(), std::move(medians));
  run.groupMs = groupTimes(r.pipeline(), times);
  if (times.has("rt_dof")) run.rtDofMs = times.ofType("rt_dof");
  run.frameMs = summarize(total).median;
  // The ray mask's counters, where it ran (the baselines have none; a row may disable it).
  run.raysPerPixel = r.context().counter(RayMaskCounters::raysPerPixel, run.raysPerPixel);
  run.maskedShare = r.context().counter(RayMaskCounters::maskedShare, run.maskedShare);
  return run;
}

Buffer referenceFor(const Scene& scene, const CameraDesc& cam, int w, int h, int spp,
                    Integrator integrator, const std::string& cache) {
  ReferenceJob job;
  job.scene = &scene;
  job.camera = job.shutterCamera = cam;
  job.width = w;
  job.height = h;
  job.settings.spp = spp;
  job.settings.integrator = integrator;
  job.settings.progress = true;
  return visualizeBuffer(referenceImage(job, cache).hdr);
}

// The ray budget m (and, with `full`, the mask at full resolution).
PipelineEdits setM(int m, bool full = false) {
  return {editPass<RayMaskPass>([=](RayMaskSettings& r) {
    r.m = m;
    if (full) r.resolution = RayMaskSettings::Resolution::Full;
  })};
}

// Table 2: pass timings per shot and ray budget.
void table2(const DofExperimentOptions& o, const std::vector<Scene>& scenes,
            ExperimentReport& report) {
  std::vector<std::vector<std::string>> timingRows;
  std::vector<std::string> header = {"pass"};
  std::vector<StaticRun> runs;
  std::vector<double> deferredMs;
  for (size_t s = 0; s < scenes.size(); ++s) {
    std::printf("experiment hybrid-dof: Table 2, shot %s\n", o.shotLabels[s].c_str());
    std::fflush(stdout);
    deferredMs.push_back(
        renderStatic(scenes[s], "deferred", {}, o.width, o.height, o.tableWarmup, o.tableFrames)
            .frameMs);
    for (int m : o.tableBudgets) {
      header.push_back(o.shotLabels[s] + " m=" + std::to_string(m));
      runs.push_back(renderStatic(scenes[s], "hybrid-dof", setM(m), o.width, o.height,
                                  o.tableWarmup, o.tableFrames));
    }
  }
  std::vector<double> grouped(runs.size(), 0.0), ours(runs.size(), 0.0);
  for (const std::string& group : table2Groups()) {
    std::vector<std::string> row{group};
    for (size_t i = 0; i < runs.size(); ++i) {
      const auto it = runs[i].groupMs.find(group);
      const double v = it == runs[i].groupMs.end() ? 0.0 : it->second;
      grouped[i] += v;
      if (group != "post-process" && group.rfind("sharp", 0) != 0 && group != "final TAA")
        ours[i] += v;
      row.push_back(fmt(v, 2));
    }
    timingRows.push_back(row);
  }
  std::vector<std::string> others{"others (tonemap, history, scene update)"},
      ourRow{"ours (ray mask .. composite)"}, total{"total frame"}, fps{"frame rate"},
      deferredRow{"deferred frame, same shot"}, ratioRow{"hybrid-dof / deferred"},
      rays{"rays per mask pixel (mean)"}, masked{"masked share of mask pixels"};
  for (size_t i = 0; i < runs.size(); ++i) {
    const double d = deferredMs[i / o.tableBudgets.size()];
    others.push_back(fmt(std::max(runs[i].frameMs - grouped[i], 0.0), 2));
    ourRow.push_back(fmt(ours[i], 2));
    total.push_back(fmt(runs[i].frameMs, 1));
    fps.push_back(fmt(1000.0 / runs[i].frameMs, 2));
    deferredRow.push_back(fmt(d, 1));
    ratioRow.push_back(fmt(runs[i].frameMs / d, 2));
    rays.push_back(fmt(runs[i].raysPerPixel, 2));
    masked.push_back(fmt(runs[i].maskedShare, 3));
  }
  for (auto* r : {&others, &ourRow, &total, &fps, &deferredRow, &ratioRow, &rays, &masked})
    timingRows.push_back(*r);
  report.markdown("### Table 2 shape: pass durations (ms) and frame rates, " +
                  std::to_string(o.width) + "x" + std::to_string(o.height) + "\n\n");
  report.table("table2_pass_ms", header, timingRows);
}

struct SweepPoint {
  int m;
  double ssim, ms;
};

// What Figure 7's sweep leaves for the equal-quality table and Figure 6.
struct Figure7 {
  Buffer ref, refPt;  // the same-shading and the path-traced reference
  StaticRun postfx;
  double postfxSsim = 0;
  Buffer hybrid10, rt10;  // at m = 10 (or the first budget)
  double hybridSsim10 = -1, hybridMs10 = 0;
  std::vector<SweepPoint> rtPoints, hybridPoints, fullPoints;
};

// Figure 7 on one shot: quality against the ray budget m, against the same-shading reference.
Figure7 figure7(const DofExperimentOptions& o, const Scene& fig, const std::string& figLabel,
                ExperimentReport& report) {
  Figure7 out;
  const int sw = o.sweepWidth, sh = o.sweepHeight;
  std::printf("experiment hybrid-dof: Figure 7, shot %s, references\n", figLabel.c_str());
  std::fflush(stdout);
  const CameraDesc figCam = defaultCamera(fig);
  const Buffer ref =
      referenceFor(fig, figCam, sw, sh, o.referenceSpp, Integrator::Whitted, o.cache);
  const Buffer refPt =
      referenceFor(fig, figCam, sw, sh, o.pathReferenceSpp, Integrator::Path, o.cache);
  const StaticRun postfx = renderStatic(fig, "postfx-dof", {}, sw, sh, o.warmup, o.frames);
  const double postfxSsim = ssim(postfx.image, ref), postfxFlip = flip(ref, postfx.image);
  const double postfxRmse = rmse(postfx.image, ref);
  PlotSeries sH{"hybrid-dof", {}, {}}, sR{"rt-dof", {}, {}}, sP{"postfx-dof", {}, {}};
  PlotSeries fH{"hybrid-dof", {}, {}}, fR{"rt-dof", {}, {}}, fP{"postfx-dof", {}, {}};
  PlotSeries tH{"hybrid-dof frame", {}, {}}, tR{"rt-dof frame", {}, {}},
      tT{"hybrid-dof ray trace", {}, {}};
  // Beyond the paper: the mask and the lens rays at full resolution (`ray_mask.resolution`).
  PlotSeries sF{"hybrid-dof, full-res rays", {}, {}}, tF{"hybrid-dof full-res frame", {}, {}};
  std::vector<std::vector<std::string>> sweepRows;
  Buffer hybrid10, rt10;
  double hybridSsim10 = -1, hybridMs10 = 0;
  std::vector<SweepPoint> rtPoints, hybridPoints, fullPoints;
  for (int m : o.sweepBudgets) {
    std::printf("experiment hybrid-dof: Figure 7, m = %d\n", m);
    std::fflush(stdout);
    const StaticRun h = renderStatic(fig, "hybrid-dof", setM(m), sw, sh, o.warmup, o.frames);
    const StaticRun r = renderStatic(fig, "rt-dof", setM(m), sw, sh, o.warmup, o.frames);
    const StaticRun f = renderStatic(fig, "hybrid-dof", setM(m, true), sw, sh, o.warmup, o.frames);
    const double hs = ssim(h.image, ref), rs = ssim(r.image, ref), fss = ssim(f.image, ref);
    const double hf = flip(ref, h.image), rf = flip(ref, r.image);
    sweepRows.push_back({std::to_string(m), fmt(hs, 4), fmt(hf, 4), fmt(rmse(h.image, ref), 4),
                         fmt(h.frameMs, 1), fmt(h.rtDofMs, 1), fmt(rs, 4), fmt(rf, 4),
                         fmt(rmse(r.image, ref), 4), fmt(r.frameMs, 1), fmt(postfxSsim, 4),
                         fmt(postfxFlip, 4), fmt(postfxRmse, 4), fmt(fss, 4), fmt(f.frameMs, 1)});
    const double x = m;
    sF.x.push_back(x), sF.y.push_back(fss), tF.x.push_back(x), tF.y.push_back(f.frameMs);
    fullPoints.push_back({m, fss, f.frameMs});
    sH.x.push_back(x), sH.y.push_back(hs), sR.x.push_back(x), sR.y.push_back(rs);
    sP.x.push_back(x), sP.y.push_back(postfxSsim);
    fH.x.push_back(x), fH.y.push_back(hf), fR.x.push_back(x), fR.y.push_back(rf);
    fP.x.push_back(x), fP.y.push_back(postfxFlip);
    tH.x.push_back(x), tH.y.push_back(h.frameMs), tR.x.push_back(x), tR.y.push_back(r.frameMs);
    tT.x.push_back(x), tT.y.push_back(h.rtDofMs);
    rtPoints.push_back({m, rs, r.frameMs});
    hybridPoints.push_back({m, hs, h.frameMs});
    if (m == 10 || hybridSsim10 < 0) {
      hybrid10 = h.image;
      rt10 = r.image;
      hybridSsim10 = hs;
      hybridMs10 = h.frameMs;
    }
  }
  report.markdown("### Figure 7 shape: quality against the ray budget m (shot " + figLabel + ", " +
                  std::to_string(sw) + "x" + std::to_string(sh) +
                  "), against distributed ray tracing of the same shading (" +
                  std::to_string(o.referenceSpp) + " spp)\n\n");
  report.table(
      "figure7_quality_vs_m",
      {"m", "hybrid SSIM", "hybrid FLIP", "hybrid RMSE", "hybrid frame ms", "hybrid ray trace ms",
       "rt-dof SSIM", "rt-dof FLIP", "rt-dof RMSE", "rt-dof frame ms", "postfx SSIM", "postfx FLIP",
       "postfx RMSE", "full-res hybrid SSIM", "full-res hybrid frame ms"},
      sweepRows);
  report.plot("figure7_ssim", "SSIM against the same-shading reference", "ray budget m", "SSIM",
              {sH, sR, sP, sF}, true);
  report.plot("figure7_flip", "FLIP against the same-shading reference", "ray budget m", "FLIP",
              {fH, fR, fP}, true);
  report.plot("figure7_ms", "Frame and ray-trace time", "ray budget m", "ms", {tH, tR, tT, tF},
              true);
  out.ref = ref;
  out.refPt = refPt;
  out.postfx = postfx;
  out.postfxSsim = postfxSsim;
  out.hybrid10 = hybrid10;
  out.rt10 = rt10;
  out.hybridSsim10 = hybridSsim10;
  out.hybridMs10 = hybridMs10;
  out.rtPoints = rtPoints;
  out.hybridPoints = hybridPoints;
  out.fullPoints = fullPoints;
  return out;
}

// Speed at equal quality: where the hybrid stands on rt-dof's curve.
void equalQualityTable(const DofExperimentOptions& o, const Figure7& f7, ExperimentReport& report) {
  const std::vector<SweepPoint>& rtPoints = f7.rtPoints;
  const double hybridSsim10 = f7.hybridSsim10, hybridMs10 = f7.hybridMs10,
               postfxSsim = f7.postfxSsim;
  // Speed at equal quality: the cheapest rt-dof point of the sweep at least as good as `ssim`
  // (null if none is), first for hybrid-dof at m = 10.
  auto cheapestRtAtLeast = [&](double ssimAtLeast) -> const SweepPoint* {
    const SweepPoint* best = nullptr;
    for (const SweepPoint& p : rtPoints)
      if (p.ssim >= ssimAtLeast && (!best || p.ms < best->ms)) best = &p;
    return best;
  };
  const SweepPoint* rtEqual = cheapestRtAtLeast(hybridSsim10);
  const double rtEqualMs = rtEqual ? rtEqual->ms : 0.0;
  std::string speed = "- hybrid-dof at m = 10: SSIM " + fmt(hybridSsim10, 4) + ", " +
                      fmt(hybridMs10, 1) + " ms a frame; postfx-dof: SSIM " + fmt(postfxSsim, 4) +
                      " (hybrid − postfx = " + fmt(hybridSsim10 - postfxSsim, 4) + ")\n";
  speed += rtEqualMs > 0 ? "- the cheapest rt-dof with at least that SSIM: " + fmt(rtEqualMs, 1) +
                               " ms a frame, " + fmt(rtEqualMs / hybridMs10, 2) + "x hybrid-dof's\n"
                         : "- no rt-dof budget in the sweep reaches hybrid-dof's SSIM at m = 10\n";
  // The same for every budget of the sweep: where the hybrid stands on rt-dof's curve.
  std::vector<std::vector<std::string>> equalRows;
  const SweepPoint* rtBest = nullptr;  // the sweep's best rt-dof, for "beyond the sweep"
  for (const SweepPoint& p : rtPoints)
    if (!rtBest || p.ssim > rtBest->ssim) rtBest = &p;
  auto equalPoint = [&](const std::string& resolution, const SweepPoint& hp) {
    const SweepPoint* rp = cheapestRtAtLeast(hp.ssim);
    equalRows.push_back(
        {resolution, std::to_string(hp.m), fmt(hp.ssim, 4), fmt(hp.ms, 1),
         rp ? std::to_string(rp->m) : "none (best: m = " + std::to_string(rtBest->m) + ")",
         rp ? fmt(rp->ms, 1) : "> " + fmt(rtBest->ms, 1),
         rp ? fmt(rp->ms / hp.ms, 2) + "x" : "> " + fmt(rtBest->ms / hp.ms, 2) + "x"});
  };
  for (const SweepPoint& hp : f7.hybridPoints) equalPoint("half (paper)", hp);
  for (const SweepPoint& hp : f7.fullPoints) equalPoint("full", hp);
  speed += "\n";
  report.markdown(speed);
  speed.clear();
  report.table("figure7_equal_quality",
               {"hybrid rays", "hybrid m", "hybrid SSIM", "hybrid ms",
                "cheapest rt-dof m with at least that SSIM", "its ms", "rt-dof / hybrid"},
               equalRows);
  speed += "\n- against the path-traced reference (" + std::to_string(o.pathReferenceSpp) +
           " spp; includes global illumination, which none of the three models): SSIM hybrid " +
           fmt(ssim(f7.hybrid10, f7.refPt), 4) + ", postfx " +
           fmt(ssim(f7.postfx.image, f7.refPt), 4) + ", rt-dof " + fmt(ssim(f7.rt10, f7.refPt), 4) +
           "\n\n";
  report.markdown(speed);
}

// Figure 6: crops and FLIP maps.
void figure6(const DofExperimentOptions& o, const Figure7& f7, const std::string& figLabel,
             ExperimentReport& report) {
  const Buffer& ref = f7.ref;
  const std::vector<std::pair<std::string, const Buffer*>> crops = {
      {"reference", &ref},
      {"postfx-dof", &f7.postfx.image},
      {"hybrid-dof", &f7.hybrid10},
      {"rt-dof", &f7.rt10}};
  for (const auto& [name, img] : crops) {
    const std::string file = "figure6_" + name + ".png";
    writePng((fs::path(o.out) / file).string(), cropOf(*img, o.crop));
    report.image(file, figLabel + ": " + name + " (m = 10), crop");
    if (img != &ref) {
      Buffer map;
      flip(ref, *img, &map);
      const std::string mf = "figure6_" + name + "_flip.png";
      writePng((fs::path(o.out) / mf).string(), cropOf(flipColorMap(map), o.crop));
      report.image(mf, figLabel + ": FLIP of " + name + " against the reference");
    }
  }
}

// Temporal: along each shot's camera path, per-frame references at a small size.
void temporalTable(const DofExperimentOptions& o, const std::vector<Scene>& scenes,
                   ExperimentReport& report) {
  std::vector<std::vector<std::string>> temporalRows;
  for (size_t s = 0; s < scenes.size() && o.temporalFrames > 0; ++s) {
    const Scene& scene = scenes[s];
    if (scene.cameraPath.size() < 2) continue;
    std::printf("experiment hybrid-dof: temporal, shot %s\n", o.shotLabels[s].c_str());
    std::fflush(stdout);
    const CameraDesc base = defaultCamera(scene);
    for (bool adaptive : {false, true}) {
      Pipeline p = Pipeline::load("hybrid-dof");
      editPass<DofAccumulationPass>(
          [&](DofAccumulationSettings& a) { a.adaptiveAlpha = adaptive; })(p);
      Renderer r(scene, std::move(p),
                 RenderSettings{.width = o.temporalWidth, .height = o.temporalHeight});
      r.keepOnDevice();  // only the frames compared are read back
      double sum = 0, worst = 1;
      int n = 0;
      for (int f = 0; f < o.temporalFrames; ++f) {
        const CameraDesc c = pathCamera(scene, base, f, o.temporalFrames);
        r.renderFrame(f, c);
        if (f == 0 || f % o.temporalEvery) continue;
        const Buffer fr = referenceFor(scene, c, o.temporalWidth, o.temporalHeight, o.temporalSpp,
                                       Integrator::Whitted, o.cache);
        const double v = ssim(r.output(), fr);
        sum += v;
        worst = std::min(worst, v);
        ++n;
      }
      // A path too short for one compared frame says so instead of a score.
      temporalRows.push_back({o.shotLabels[s], adaptive ? "on" : "off (paper)",
                              n ? fmt(sum / n, 4) : "—", n ? fmt(worst, 4) : "—",
                              std::to_string(n)});
    }
  }
  if (!temporalRows.empty()) {
    report.markdown("### Temporal: the camera path (" + std::to_string(o.temporalFrames) +
                    " frames, every " + std::to_string(o.temporalEvery) +
                    "-th against its own reference at " + std::to_string(o.temporalSpp) + " spp, " +
                    std::to_string(o.temporalWidth) + "x" + std::to_string(o.temporalHeight) +
                    ")\n\n");
    report.table("temporal_ssim",
                 {"shot", "per-pixel blend factors", "mean SSIM", "worst-frame SSIM", "frames"},
                 temporalRows);
  }
}

}  // namespace

int runDofExperiment(const DofExperimentOptions& o) {
  if (o.shots.empty()) throw InputError("experiment", "shots", "no shots");
  std::vector<Scene> scenes;
  for (const std::string& s : o.shots) scenes.push_back(loadScene(s));
  for (const char* p : {"hybrid-dof", "postfx-dof", "rt-dof", "deferred"}) Pipeline::load(p);
  fs::create_directories(o.out);
  ExperimentReport report(o.out, "Tan et al. 2022: hybrid depth of field");
  table2(o, scenes, report);
  // Figures 6 and 7 on one shot, against the same-shading reference.
  const size_t figShot = o.figureShot >= 0 ? size_t(o.figureShot) : scenes.size() - 1;
  const Figure7 f7 = figure7(o, scenes[figShot], o.shotLabels[figShot], report);
  equalQualityTable(o, f7, report);
  figure6(o, f7, o.shotLabels[figShot], report);
  temporalTable(o, scenes, report);
  const int sw = o.sweepWidth, sh = o.sweepHeight;
  char settings[256];
  std::snprintf(settings, sizeof settings,
                "timings %dx%d (%d warm-up + %d timed frames), quality %dx%d (%d warm-up + %d "
                "measured frames per static shot)",
                o.width, o.height, o.tableWarmup, o.tableFrames, sw, sh, o.warmup, o.frames);
  report.write(settings);
  return 0;
}

}  // namespace tandem
