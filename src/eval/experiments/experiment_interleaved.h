// `tandem experiment interleaved`: Foster 2015's interleaved sampling, measured.
//  - tile quality: minimum and mean distance between samples of similar times, per-footprint
//    discrepancy of times and lens positions, random against colored-corner tiles, per (N, k);
//  - error against the same-shading reference (pt_reference integrator=whitted at the same
//    shutter and aperture: the interleaved passes shade with the same Whitted function, so the
//    error measures sampling alone) — RMSE, SSIM, FLIP against N at a fixed k and against k at a
//    fixed N, for each sampling scheme, and the accumulation baseline (N whole images);
//  - time per frame: interleaved rasterization against interleaved ray tracing at equal samples
//    and against brute force (accumulation), with Whitted and with local shading;
//  - strobing at small N: decorrelated against correlated (time, lens) pairs, with crops;
//  - hybrid motion blur against post-process-only and full interleaved sampling, with times.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tandem {

struct InterleavedExperimentOptions {
  std::string out = "out/experiment-interleaved";
  std::string cache;  // reference cache folder ("" = none)
  std::vector<std::string> scenes, sceneLabels;
  float shutter = 0.1f;           // seconds
  int width = 320, height = 180;  // quality sweeps
  int referenceSpp = 256;
  int seeds = 3;  // frames (seeds) averaged per quality point
  std::vector<int> pairCounts{4, 8, 16, 32, 64};
  int sweepSpp = 4;  // k of the N sweep
  std::vector<int> sppCounts{1, 4, 16};
  int sweepPairs = 16;  // N of the k sweep
  int timingWidth = 960, timingHeight = 540, timingFrames = 3, timingWarmup = 1;
  int timingPairs = 16, timingSpp = 4;
  int strobePairs = 4;
  // Hybrid motion blur: frames of a moving sequence (1/30 s apart from time 0); errors on the
  // last one against a reference at its time, time per frame the median after the first.
  int sequenceFrames = 10;
  int crop[4] = {0, 0, 0, 0};  // strobing crop at the quality size (0: centre third)
};

InterleavedExperimentOptions interleavedOptionsFromJson(const nlohmann::json& j,
                                                        const std::string& file);
int runInterleavedExperiment(const InterleavedExperimentOptions& o);

}  // namespace tandem
