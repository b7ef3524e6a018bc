// A supersampled ground truth for anti-aliasing: the pipeline rendered at n x n stratified
// sub-pixel offsets (cell centres of an n x n grid over the pixel) and averaged — the same
// shading and light transport, only the pixel filter differs (a box over the pixel area).
#pragma once
#include <string>

#include "pipeline/renderer.h"

namespace tandem {

// Mean of buffer `buffer` over n * n jittered renders of one frame (n >= 1). Empty `buffer`: the
// linear colour the pipeline's output is made from (the `hdr` input of the pass writing the
// output, e.g. `composite` in the hybrid pipelines).
Buffer supersample(const Scene& scene, const std::string& pipeline, const CameraDesc& camera,
                   const RenderSettings& settings, int n, const std::string& buffer = "");
// The buffer named above for an empty `buffer`.
std::string outputSource(const Pipeline& p);

}  // namespace tandem
