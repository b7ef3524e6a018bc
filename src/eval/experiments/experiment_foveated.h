// `tandem experiment foveated`: Peres 2022's evaluation (§6), reproduced in kind.
//  - Table 2: the region distribution (radius, area, the thesis' samples = area x spp, spp) of
//    each resolution, with the pixels and samples actually listed after the selection toss;
//  - Table 4 shape: mean ms per frame along each scene's camera path and the speed-up of NH2LD
//    and NH3LD over Base, at fhd and quest2 (the distribution is computed before the timed frames,
//    as in the thesis);
//  - Table 5 shape: RMSE, SSIM and PSNR of each configuration against the same path tracer
//    without foveation or denoising (reference integrator diffuse-gi, `referenceSpp`), over the
//    whole dual image and separately in the fovea (inner layer) and the periphery (outer layer);
//  - Figures 17 and 18: same-crop comparisons and FLIP heat maps side by side;
//  - beyond the thesis: NH3LD with the periphery accumulated over frames, its selection rotating
//    each frame and its level counts from the measured noise (foveated-nh3ld-temporal; timed
//    along the path, its quality after `temporalFrames` frames of the still camera, also with
//    the thesis' fixed selection and levels), and NH3LD with each region's level count from its
//    measured noise (nh_denoise levels_from = variance);
//  - the accumulating configuration along a moving camera (Base, NH3LD, NH3LD + temporal at the
//    last of the first `temporalFrames` frames of each path, against its own reference).
// Quality is measured at a smaller size (`qualityWidth` x `qualityHeight` per eye, radii scaled
// from the FHD ones by the eye's height) so the references stay affordable on a CPU.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tandem {

struct FoveatedExperimentOptions {
  std::string out = "out/experiment-foveated";
  std::string cache;  // reference cache folder ("" = none)
  std::vector<std::string> scenes, sceneLabels;
  std::vector<std::string> resolutions{"fhd", "quest2"};
  int warmup = 1;                               // untimed frames (the distribution is built)
  int fhdFrames = 4, quest2Frames = 2;          // timed frames along the camera path
  int qualityWidth = 480, qualityHeight = 540;  // per eye
  int referenceSpp = 1024;
  int temporalFrames = 8;  // still-camera frames before NH3LD + temporal is measured
  // Moving camera: the first temporalFrames frames of each path at 30 fps at this size, the last
  // against its own reference (pathReferenceSpp; 0: skipped).
  int pathWidth = 240, pathHeight = 270, pathReferenceSpp = 256;
  int crop[4] = {0, 0, 0, 0};  // Figure 17 crop of the left eye at the quality size (0: centre)
};

FoveatedExperimentOptions foveatedOptionsFromJson(const nlohmann::json& j, const std::string& file);
int runFoveatedExperiment(const FoveatedExperimentOptions& o);

}  // namespace tandem
