// `tandem experiment hybrid-dof`: Tan et al. 2022's evaluation, reproduced in kind.
//  - Table 2 shape: ms per pass group (sharp image, post-process, G-buffer & σ² (ray mask), ray
//    trace, accumulation, median + reconstruction, composite, final TAA, others) of hybrid-dof on
//    the BG / M / FG shots at m = 1, 30, 50, with the deferred frame of the same shot beside it;
//  - Figure 7 shape: SSIM, FLIP and RMSE against the same-shading reference (distributed ray
//    tracing of the Whitted shading, pt_reference integrator=whitted) against the ray budget m
//    for hybrid-dof and rt-dof, with postfx-dof as a flat line, and frame / ray-trace ms against m;
//    the m = 10 images also against the path-traced reference (labelled: includes global
//    illumination);
//  - Figure 6 shape: crops of the defocused foreground silhouette in the reference, postfx-dof,
//    hybrid-dof and rt-dof images, with FLIP maps;
//  - temporal: mean and worst-frame SSIM along each shot's camera path against per-frame
//    references at a small size, with the accumulation's per-pixel blend factors off and on.
// Static shots are rendered `warmup` frames (the accumulation converging) and measured over
// `frames` more; Table 2's timings over `tableFrames` after `tableWarmup`.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tandem {

struct DofExperimentOptions {
  std::string out = "out/experiment-hybrid-dof";
  std::string cache;  // reference cache folder ("" = none)
  std::vector<std::string> shots, shotLabels;
  int width = 960, height = 540;             // Table 2 (timings)
  int sweepWidth = 480, sweepHeight = 270;   // Figure 7 and 6 (quality)
  int warmup = 24, frames = 8;               // static shots (quality)
  int tableWarmup = 4, tableFrames = 4;      // Table 2 (timings need no converged image)
  std::vector<int> tableBudgets{1, 30, 50};  // m for Table 2
  std::vector<int> sweepBudgets{1, 2, 5, 10, 20, 30, 50};
  int figureShot = -1;  // index of the shot for Figures 6-7 (-1: last)
  int referenceSpp = 256, pathReferenceSpp = 256;
  int crop[4] = {0, 0, 0, 0};  // Figure 6 crop at the sweep size (0: centre third)
  int temporalWidth = 240, temporalHeight = 135, temporalFrames = 30, temporalEvery = 3;
  int temporalSpp = 64;
};

DofExperimentOptions dofOptionsFromJson(const nlohmann::json& j, const std::string& file);
int runDofExperiment(const DofExperimentOptions& o);

}  // namespace tandem
