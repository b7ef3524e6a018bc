// LDR-FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG 2020):
// the perceived difference between a reference and a test image as they would be flipped
// between on a display, per pixel in [0, 1]. Two pipelines:
//  - colour: both images in YCxCz, filtered by the contrast sensitivity of each opponent channel
//    at the viewing distance (pixels per degree), then compared in Hunt-adjusted L*a*b* with
//    the HyAB distance, compressed (exponent 0.7) and remapped to [0, 1];
//  - features: edges and points (first and second Gaussian derivatives of the achromatic
//    channel) found in one image and not the other.
// FLIP = colour^(1 - features). Inputs are display-encoded sRGB in [0, 1] (tonemap HDR first).
#pragma once
#include "core/buffer.h"

namespace tandem {

// A 0.7 m wide 3840-pixel monitor seen from 0.7 m (the paper's default): 67 pixels per degree.
double defaultPixelsPerDegree();

// Mean FLIP over the image; `map` (optional) receives the per-pixel error (1 channel).
double flip(const Buffer& reference, const Buffer& test, Buffer* map = nullptr,
            double pixelsPerDegree = defaultPixelsPerDegree());

// An error map in a perceptual black-purple-orange-yellow ramp (0 black, 1 pale yellow).
Buffer flipColorMap(const Buffer& error);

}  // namespace tandem
