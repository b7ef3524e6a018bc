// Interleaved sampling for depth of field and motion blur (seed 003; Fatahalian et al. 2009).
// Per frame the set T of N (time, lens) pairs (raster/sample_tiles.h); the image's samples, k per
// pixel on a grid of strata, each take one pair (raster/sample_layout.h: the sampling scheme).
// Visibility is found once per pair of T:
//  - interleaved_raster: the scene rasterized at that pair (objects at its time, the camera at its
//    lens point with the projection sheared so the focus plane stays put), writing only the
//    samples that carry the pair into one supersampled visibility buffer; with tiles, one sample
//    per tile, so each pass is bounded by the region its triangles cover at that pair;
//  - interleaved_rt: each sample's primary ray at its pair's time (Embree motion blur) from its
//    lens point: the same samples, ray traced.
// Both shade every sample with the one shading function (Whitted: ray-traced shadows, mirrors,
// glass at the pair's time; or `local` Blinn-Phong without shadows, as accumulation) and resolve
// to pixels with a box or Blackman-Harris filter of the given radius.
// Outputs: hdr; interleave_samples (the strata grid, W k_x x H k_y: time, lens u1, u2, tile
// prototype / 80) for the viewer. Counters: triangles set up per pass (raster).
#pragma once
#include <memory>

#include "pipeline/pass.h"
#include "raster/rasterizer.h"
#include "raster/sample_layout.h"
#include "scene/camera.h"

namespace tandem {

struct View;

// The camera of view `v` at pair p: along its shutter path at p.tau (if `time`), moved to the
// lens point (u1, u2) (if `lens`) with the projection sheared, plus a sub-pixel jitter.
Camera cameraForPair(const View& v, const TimeLensPair& p, bool time, bool lens, Vec2 jitter);

// The Blackman-Harris window at |x| / radius in [0, 1] (1 at the centre, ~0 at the radius).
float blackmanHarris(float t);

class InterleavedPass : public Pass {
 public:
  std::vector<BufferSlot> outputs() const override {
    return {{"hdr", 3}, {"interleave_samples", 4, BufferKind::Color, Extent::any()}};
  }
  std::vector<ParamDesc> params() const override;
  void execute(FrameContext& ctx) override;

 protected:
  // Finds the surface of every sample: vis.object / vis.prim indexed by sample id.
  virtual void visibility(FrameContext& ctx, const SampleLayout& layout,
                          const std::vector<Camera>& cams, const std::vector<float>& taus,
                          VisibilityBuffer& vis) = 0;
  virtual bool tracesPrimaryRays() const { return false; }

 private:
  std::unique_ptr<SampleLayout> layout_;
  uint64_t layoutKey_ = 0;
  VisibilityBuffer vis_;
  std::vector<Vec3> colour_;
};

class InterleavedRasterPass : public InterleavedPass {
 public:
  std::string type() const override { return "interleaved_raster"; }
  std::string description() const override {
    return "Interleaved rasterization: one pass per (time, lens) pair of T into the samples "
           "whose tile slot carries it (seed 003)";
  }

 protected:
  void visibility(FrameContext& ctx, const SampleLayout& layout, const std::vector<Camera>& cams,
                  const std::vector<float>& taus, VisibilityBuffer& vis) override;

 private:
  Rasterizer rasterizer_;
};

class InterleavedRTPass : public InterleavedPass {
 public:
  std::string type() const override { return "interleaved_rt"; }
  std::string description() const override {
    return "Interleaved ray tracing: each sample's primary ray at its pair's time and lens point "
           "(seed 003, the same tiles)";
  }

 protected:
  void visibility(FrameContext& ctx, const SampleLayout& layout, const std::vector<Camera>& cams,
                  const std::vector<float>& taus, VisibilityBuffer& vis) override;
  bool tracesPrimaryRays() const override { return true; }
};

}  // namespace tandem
