// tandem compare A B: RMSE, PSNR, SSIM and LDR-FLIP between two images, optional SSIM heat map
// and FLIP error map. FLIP sees images as displayed: EXRs are tonemapped (ACES) to sRGB first.
#include <cstdio>
#include <memory>

#include "core/error.h"
#include "core/image_io.h"
#include "eval/metrics/flip.h"
#include "eval/metrics/metrics.h"
#include "pipeline/aov.h"
#include "verbs.h"

namespace tandem {

VerbRunner addCompareVerb(CLI::App& app) {
  struct Args {
    std::string a, b, heatmap, flipMap;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "compare", "Compare two images: RMSE, PSNR, SSIM (per RGB channel, averaged) and FLIP");
  sub->add_option("a", args->a, "First image (PNG or EXR)")->required();
  sub->add_option("b", args->b, "Second image (PNG or EXR)")->required();
  sub->add_option("--heatmap", args->heatmap, "Write a PNG heat map of 1 - SSIM");
  sub->add_option("--flip-map", args->flipMap, "Write the FLIP error map as PNG (a = reference)");
  return [args] {
    Buffer a = loadImage(args->a), b = loadImage(args->b);
    if (a.width != b.width || a.height != b.height)
      throw InputError(args->b, "size",
                       std::to_string(b.width) + "x" + std::to_string(b.height) + " differs from " +
                           args->a + " (" + std::to_string(a.width) + "x" +
                           std::to_string(a.height) + ")");
    requireFinitePixels(a, args->a, "pixels");
    requireFinitePixels(b, args->b, "pixels");
    Buffer map;
    ImageMetrics m = compareImages(a, b, args->heatmap.empty() ? nullptr : &map);
    // FLIP compares what a viewer sees: HDR images tonemapped as `render` writes them.
    auto display = [](const std::string& path, const Buffer& img) {
      return hasExtension(path, ".exr") ? visualizeBuffer(img) : img;
    };
    Buffer flipErrors;
    const double f = flip(display(args->a, a), display(args->b, b), &flipErrors);
    std::printf("rmse %.6f\npsnr %.3f dB\nssim %.6f\nflip %.6f\n", m.rmse, m.psnr, m.ssim, f);
    if (!args->flipMap.empty()) {
      writePng(args->flipMap, flipColorMap(flipErrors));
      std::printf("wrote %s\n", args->flipMap.c_str());
    }
    if (!args->heatmap.empty()) {
      for (float& v : map.data) v = 1.0f - v;
      writePng(args->heatmap, heatMap(map, 1.0f));
      std::printf("wrote %s\n", args->heatmap.c_str());
    }
    return 0;
  };
}

}  // namespace tandem
