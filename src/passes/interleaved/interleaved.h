// Interleaved sampling for depth of field and motion blur (Foster 2015; Fatahalian et al. 2009).
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
// to pixels with a box or Blackman-Harris filter of the given radius. `shading_rate = pixel`
// shades a pixel's samples that see the same triangle at the same pair once (MSAA-style: the
// sharp mid-shutter image of the post-process motion blur, anti-aliased at the cost of ~1 shade
// a pixel).
// Input (optional): sample_mask — where to sample (> 0); elsewhere no sample is shaded and hdr
// is 0 (hybrid motion blur samples only where the post-process cannot be trusted).
// Outputs: hdr; for the viewer sample_time_lens (the strata grid, W k_x x H k_y: each sample's
// shutter fraction, lens u1, u2 as red, green, blue) and tile_layout (each pixel's tile
// prototype, 0-80, false-coloured; -1 for the schemes without tiles); velocity (the screen
// displacement in pixels over the whole shutter of the surface a pixel's first sample sees: camera
// open to close, object at open to close) and view_depth (that surface's distance along the view
// axis) for the post-process motion blur; motion (written only when a pass reads it: the
// screen motion in pixels since the previous frame of that surface at the same shutter fraction,
// for temporal AA of a sharp image with `view_jitter`). Counters: triangles set up per pass
// (raster).
#pragma once
#include <memory>

#include "core/buffer.h"
#include "passes/common/whitted_settings.h"
#include "pipeline/param_table.h"
#include "raster/rasterizer.h"
#include "raster/sample_layout.h"
#include "raster/sample_tiles.h"
#include "scene/camera.h"

namespace tandem {

struct View;

// The Blackman-Harris window at |x| / radius in [0, 1] (1 at the centre, ~0 at the radius).
float blackmanHarris(float t);

struct InterleavedSettings {
  enum class Mode { Dof, MotionBlur, Both };  // what the pairs vary
  enum class Filter { Box, BlackmanHarris };
  enum class Shading { Whitted, Local };
  enum class ShadingRate { Sample, Pixel };
  int samples = 16;  // N
  int spp = 4;       // k
  SamplingScheme scheme = SamplingScheme::ColoredCorner;
  Mode mode = Mode::Both;
  bool correlated = false;
  bool jitter = true;
  Filter filter = Filter::Box;
  float filterRadius = 0.5f;
  Shading shading = Shading::Whitted;
  float shutterTime = -1;
  ShadingRate shadingRate = ShadingRate::Sample;
  float textureFootprint = 1;
  bool viewJitter = false;
  WhittedParams whitted{};
  bool lens() const { return mode != Mode::MotionBlur; }
  bool time() const { return mode != Mode::Dof; }
};

// The channels of sample_time_lens, one per sample of the strata grid: its shutter fraction and
// lens coordinates (shown as red, green, blue).
struct SampleChannels {
  static constexpr int kTime = 0, kLensU = 1, kLensV = 2, kCount = 3;
  static BufferSlot slot() {
    return BufferSlot{"sample_time_lens", 0, BufferKind::Mask, Extent::any()}.named(
        {"time", "lens_u", "lens_v"});
  }
};

// The counters every interleaved pass reports, under its type: "<type>/passes", ... (with Whitted
// shading also whittedCounters()).
struct InterleavedCounters {
  explicit InterleavedCounters(const Pass& pass) : key(pass.type() + "/") {}
  std::string key;
  std::string passes() const { return key + "passes"; }
  std::string samplesPerPixel() const { return key + "samples_per_pixel"; }
  std::string minSimilarTimeDistance() const { return key + "min_similar_time_distance_px"; }
  std::string footprintTimeDiscrepancy() const { return key + "footprint_time_discrepancy"; }
};

class InterleavedPass : public SettingsPass<InterleavedSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
    static constexpr const char* motion = "motion";
    static constexpr const char* sampleMask = "sample_mask";
    static constexpr const char* sampleTimeLens = "sample_time_lens";
    static constexpr const char* tileLayout = "tile_layout";
    static constexpr const char* velocity = "velocity";
    static constexpr const char* viewDepth = "view_depth";
  };
  std::vector<BufferSlot> inputs() const override {
    BufferSlot mask{Slots::sampleMask, 1, BufferKind::Mask};
    mask.optional = true;
    return {mask};
  }
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::hdr, 3},
            SampleChannels::slot(),
            {Slots::tileLayout, 1, BufferKind::Id},
            {Slots::velocity, 2, BufferKind::Motion},
            {Slots::viewDepth, 1, BufferKind::Color},
            {Slots::motion, 2, BufferKind::Motion}};
  }
  void execute(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;

 protected:
  const ParamTable<InterleavedSettings>& tableFor() const override;
  // Finds the surface of every sample: vis.object / vis.prim indexed by sample id. `active`
  // (null: all) marks the samples that are needed; others may be left as they are.
  virtual void visibility(FrameContext& ctx, const SampleLayout& layout,
                          const std::vector<Camera>& cams, const std::vector<float>& taus,
                          const uint8_t* active, VisibilityBuffer& vis) = 0;
  virtual bool tracesPrimaryRays() const { return false; }

 protected:
  // The frame's pairs (both devices): T, the tiles handing them out, each pair's shutter
  // fraction (0 without time; shutter_time when set).
  struct Pairs {
    std::vector<TimeLensPair> pairs;
    const TileSet* tiles;
    std::vector<float> taus;
  };
  Pairs framePairs(const FrameContext& ctx) const;
  // The samples of a W x H view, built when the scheme, size, seed or tiles change
  // (layoutVersion() then changes).
  const SampleLayout& layoutFor(const FrameContext& ctx, const TileSet& tiles, int W, int H);
  uint64_t layoutVersion() const { return layoutVersion_; }
  // Each pair's camera for view v: along its shutter path, at its lens point.
  std::vector<Camera> pairCameras(const View& v, const Pairs& p) const;
  void reportTiles(FrameContext& ctx, const TileSet& tiles) const;
  // What velocity and motion carry a pair's surface point with (writeMotion): per pair and
  // animated object, world at the pair's time to world at shutter open and close, and to the
  // previous frame's same shutter fraction; with `motion`, each pair's camera of this and the
  // previous frame moved as far into its shutter.
  struct MotionCarry {
    std::vector<std::vector<std::pair<Mat4, Mat4>>> carry;
    std::vector<std::vector<Mat4>> carryPrev;
    std::vector<Camera> nowCams, prevCams;
  };
  MotionCarry motionCarry(const FrameContext& ctx, const std::vector<float>& taus, const View& v,
                          bool motion) const;
  // Both passes' frame on the GPU (interleaved_gpu.cpp): visibility by the compute rasterizer
  // (interleaved_raster) or traced (interleaved_rt, !tracesPrimaryRays()), shading, resolve,
  // motion. Returns the rasterizer's counters, one a pair and view, read after the submission.
  std::vector<const uint32_t*> renderOnGpu(FrameContext& ctx);
  // For the viewer, when something reads them: sample_time_lens and tile_layout (the host's).
  void writeViewerBuffers(FrameContext& ctx, const Pairs& p, const View& v);

 private:
  struct Frame;  // what one frame's views share (interleaved.cpp)
  void renderView(FrameContext& ctx, const Frame& f, const View& v);
  // Step 0: the samples of pixels within the filter's reach of the mask (active_), and the
  // pixels resolved (the mask itself).
  void markActive(const Buffer& mask, const View& v, int reach, std::vector<uint8_t>& wanted);
  // Step 2: every needed sample's colour and surface point, pass by pass.
  void shadeSamples(FrameContext& ctx, const Frame& f, const View& v,
                    const std::vector<Camera>& cams, const uint8_t* active);
  void findRepresentatives(const Frame& f, int W, int H);  // shading_rate pixel
  // Step 3: the samples resolved to pixels.
  void resolve(const Frame& f, const View& v, Buffer& hdr, int reach,
               const std::vector<uint8_t>* wanted) const;
  // Velocity and depth (and motion) of each pixel's first sample.
  void writeMotion(FrameContext& ctx, const Frame& f, const View& v,
                   const std::vector<Camera>& cams, const uint8_t* active, Buffer& velocity,
                   Buffer& depth, Buffer* motion) const;

  std::unique_ptr<SampleLayout> layout_;
  uint64_t layoutKey_ = 0, layoutVersion_ = 0;
  std::vector<Buffer> packed_;  // the layout as the kernels read it (renderOnGpu)
  uint64_t packedVersion_ = 0;
  VisibilityBuffer vis_;
  std::vector<Vec3> colour_, position_;  // per sample: shaded colour, surface point
  std::vector<uint8_t> active_;
  std::vector<uint32_t> rep_;  // shading_rate pixel: the sample whose colour a sample takes
  double visMs_ = 0, shadeMs_ = 0, resolveMs_ = 0;
};

}  // namespace tandem
