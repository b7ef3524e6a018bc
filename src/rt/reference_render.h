// Progressive reference rendering: path-traced samples are added to per-pixel sums in batches
// until a target sample count or a time limit is reached, with a progress bar and a running
// estimate of the remaining noise (per-pixel variance of the mean). Samples come from the
// Owen-scrambled Sobol sampler keyed by (seed, pixel, sample index), so the image depends only
// on the settings, not on threads, batches or processes. A SampleCluster splits the rows between
// processes (MPI) and sums their partial images on rank 0; each pixel is rendered by exactly one
// process, so the sum is exact and K processes write the same image as one.
#pragma once
#include <functional>
#include <vector>

#include "core/buffer.h"
#include "rt/diffuse_gi.h"
#include "rt/path_tracer.h"
#include "rt/whitted.h"
#include "scene/camera.h"

namespace tandem {

// How work is shared between processes; the default is a single process.
class SampleCluster {
 public:
  virtual ~SampleCluster() = default;
  int rank() const { return rank_; }
  int ranks() const { return ranks_; }
  // Rows go to processes in interleaved stripes, which balances cost across the image.
  bool ownsRow(int y) const { return (y / kStripeRows) % ranks_ == rank_; }
  // Element-wise sum of `data` over all processes, into rank 0's copy.
  virtual void reduceSum(std::vector<double>& data) { (void)data; }
  // Rank 0's value, everywhere.
  virtual int broadcast(int value) { return value; }

  static constexpr int kStripeRows = 8;

 protected:
  int rank_ = 0, ranks_ = 1;
};

// What each sample evaluates. Path: the path tracer (global illumination). Whitted: distributed
// ray tracing (Cook et al. 1984) of the hybrids' own shading — the one Blinn-Phong function with
// ray-traced shadows, mirror and glass recursion (rt-only's and hybrid-all's light transport) —
// so a technique's error against it measures the technique (depth of field, motion blur), not a
// difference of light transport (Tan et al. 2022 §5.1 compares against exactly this).
// DiffuseGI: Peres 2022's foveated path tracer (rt/diffuse_gi.h: one random-light shadow ray, one
// cosine bounce, Lambert) through pixel centres of a pinhole, as its 1-spp G-buffer sees them:
// the converged image of the foveated pipelines without foveation or denoising (§6's reference).
enum class Integrator { Path, Whitted, DiffuseGI };
// "path", "whitted", "diffuse-gi": the names the CLI, pass parameters and experiment files use.
inline const char* integratorName(Integrator i) {
  return i == Integrator::Whitted ? "whitted" : i == Integrator::DiffuseGI ? "diffuse-gi" : "path";
}

struct ReferenceSettings {
  int spp = 1024;           // target samples per pixel
  double timeLimitS = 0.0;  // > 0: stop at the last whole batch that fits in this time
  Integrator integrator = Integrator::Path;
  PathSettings path;
  WhittedSettings whitted;  // Integrator::Whitted
  uint64_t seed = 0;
  bool progress = false;  // draw a progress bar on stderr (rank 0, terminals only)
};

struct ReferenceResult {
  int spp = 0;               // samples per pixel reached
  double seconds = 0;        // wall time of the sampling
  uint64_t rays = 0;         // rays this process traced
  double relativeError = 0;  // RMS standard error of the pixel means / mean luminance (rank 0)
};

// Running per-pixel sums: RGB and squared luminance, in double.
struct SampleSums {
  int width = 0, height = 0, samples = 0;
  std::vector<double> data;  // 4 per pixel: r, g, b, luminance^2
  void reset(int w, int h);
  // Mean radiance into hdr (3 channels) and the variance of the mean luminance into `variance`
  // (1 channel; the sample variance / n, which for scrambled Sobol samples overestimates the
  // true error, so it is a safe bound).
  void resolve(Buffer& hdr, Buffer* variance) const;
  double relativeError() const;
};

// The median over pixels of the standard error of the pixel mean relative to its luminance.
double relativeNoise(const Buffer& hdr, const Buffer& variance);

// Renders up to settings.spp samples per pixel of the rows this process owns. The camera moves
// from `open` to `close` while the shutter is open (pass the same camera for none); objects
// move as the RayTracer's FrameScene says.
ReferenceResult renderReference(const RayTracer& rt, const Scene& scene, const Camera& open,
                                const Camera& close, const ReferenceSettings& settings,
                                SampleCluster& cluster, SampleSums& sums);

// The camera at shutter fraction tau: position and look-at interpolated linearly.
Camera cameraAtShutter(const Camera& open, const Camera& close, float tau);

}  // namespace tandem
