// `tandem experiment taa`: what TAA buys, measured against a supersampled render of the same
// shading (n x n sub-pixel offsets, 64 spp by default), for pairs of pipelines without and with
// TAA (deferred / deferred-taa, hybrid-heuristic / hybrid-heuristic-taa):
//  - static shot: SSIM, PSNR and RMSE against the supersampled image, and temporal stability —
//    the mean frame-to-frame change of the displayed image once converged, for TAA and for the
//    same jitter without TAA (what the jitter alone would do);
//  - along the scene's camera path: SSIM against the supersampled image of sampled path frames,
//    and the mean frame-to-frame change (motion included, so shimmer shows as excess change);
//  - the TAA pass's and the frames' median ms;
//  - crops (a region given in the file) of the aliased, TAA and supersampled images.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tandem {

struct TaaExperimentOptions {
  std::string out = "out/experiment-taa";
  std::vector<std::string> scenes{"atrium"};
  std::vector<std::pair<std::string, std::string>> pairs{{"deferred", "deferred-taa"}};
  int width = 1280, height = 720;
  int staticFrames = 32;       // frames of the static shot (the last half measured)
  int supersample = 8;         // n: n x n offsets per supersampled frame
  int pathFrames = 0;          // frames along the camera path (0: real time at 30 fps)
  int pathEvery = 12;          // every k-th path frame is compared with its supersampled image
  int crop[4] = {0, 0, 0, 0};  // x, y, w, h of the crop images (w = 0: the centre third)
};

TaaExperimentOptions taaOptionsFromJson(const nlohmann::json& j, const std::string& file);
int runTaaExperiment(const TaaExperimentOptions& o);

}  // namespace tandem
