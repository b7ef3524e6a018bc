// Image metrics. All operate per channel on the values given (compare PNGs in their sRGB
// encoding in [0,1]; EXRs as linear values) and average over RGB channels.
//  - RMSE: sqrt(mean squared difference).
//  - PSNR: 10 log10(peak^2 / MSE), peak = 1 (infinite for identical images).
//  - SSIM: Wang et al. 2004 with an 11x11 Gaussian window (sigma 1.5), K1 = 0.01, K2 = 0.03,
//    dynamic range L = 1, computed per channel over the full image (window clipped at borders,
//    renormalised), then averaged over pixels and channels.
#pragma once
#include <string>

#include "core/buffer.h"

namespace tandem {

struct ImageMetrics {
  double rmse = 0, psnr = 0, ssim = 0;
};

double rmse(const Buffer& a, const Buffer& b);
double psnr(const Buffer& a, const Buffer& b, double peak = 1.0);
// Mean SSIM; when `map` is given it receives the per-pixel SSIM averaged over channels.
double ssim(const Buffer& a, const Buffer& b, Buffer* map = nullptr);
ImageMetrics compareImages(const Buffer& a, const Buffer& b, Buffer* ssimMap = nullptr);
// Metrics of images holding NaN or Inf would be NaN: an InputError naming `source`, `field` and
// how many pixels are not finite.
void requireFinitePixels(const Buffer& img, const std::string& source, const std::string& field);

// False-colour heat map of values in [0, maxValue] (blue -> green -> yellow -> red).
Buffer heatMap(const Buffer& scalar, float maxValue);

}  // namespace tandem
