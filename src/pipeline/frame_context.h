// Everything one frame's passes share: the evaluated scene, the views (cameras and viewports),
// the ray tracer, named buffers (with last frame's values of declared history inputs), and what
// passes report (timings, rays, counters). State private to a pass lives in the pass.
#pragma once
#include <any>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/buffer.h"
#include "core/error.h"
#include "core/profiler.h"
#include "raster/shadow_maps.h"
#include "rt/ray_tracer.h"
#include "rt/sampler.h"
#include "scene/frame_scene.h"
#include "scene/view.h"

namespace tandem {

class Pass;
class GpuFrame;

struct FrameContext {
  const Scene* scene = nullptr;
  FrameScene frame;
  std::vector<View> views;    // at least one; views[0] is the (left-eye) main camera
  int width = 0, height = 0;  // the frame: every view's viewport fits in it
  int frameIndex = 0;
  int64_t serial = -1;  // counts executed frames (frameIndex may repeat, e.g. a static shot)
  uint64_t seed = 0;
  // The random stream of the frame executed (rt/sampler.h frameSeed of seed and serial): every
  // stochastic pass seeds from it, the same on the CPU and the GPU.
  uint64_t frameSeed() const { return tandem::frameSeed(seed, serial); }
  Vec2 jitter{0, 0};              // this frame's projection jitter in pixels (View::jitter)
  float textureFootprint = 1.0f;  // RenderSettings::textureFootprint
  bool historyReset = true;       // history inputs are empty this frame (first frame or a reset)
  std::map<std::string, Buffer> buffers;
  std::map<std::string, Buffer> history;  // last frame's values of declared history inputs
  double passRays = 0;                    // a pass adds the rays it traced; the pipeline records it
  std::vector<PassTiming> passParts;      // optional sub-timings a pass reports ("pass/part")
  // Figures passes report for the frame ("spp", "raster/triangles_in", ...); cleared each frame.
  // Passes write them with report(), which checks the pass declares them (Pass::counters());
  // readers use counter() (reading with operator[] would insert the name).
  std::map<std::string, double> counters;
  // Outputs nothing reads may be skipped: with keepAllOutputs off, a pass may leave out an
  // output that no pass reads (this frame or as history), that is not the pipeline's output and
  // that the caller does not list in `wanted` (AOVs written, the viewer's shown buffer).
  bool keepAllOutputs = true;
  std::set<std::string> wanted;
  // On a GPU, what comes back to the host at the frame's end. outputToHost off: not the
  // pipeline's output (what a real-time renderer presents stays on the device; bench times
  // frames so). allToHost off: not every other output either, though keepAllOutputs computes
  // them. What stays there is read through Renderer::fetch, or moved when a CPU pass reads it.
  bool outputToHost = true;
  bool allToHost = true;
  std::set<std::string> consumed;  // what the passes read, set by Pipeline::execute
  // Checking mode (tests): each pass runs seeing only the buffers it declares (inputs, history
  // inputs, outputs), as a second device holding only what was moved to it would, and may leave
  // behind only its declared outputs; anything else is a logic_error naming the pass and buffer.
  bool isolatePasses = false;
  // The renderer's GPU side when it runs on a GPU (--device gpu): GPU passes record their work
  // into it, and the pipeline moves buffers between host and device (gpu_frame.h).
  std::shared_ptr<GpuFrame> gpu;

  const Camera& camera() const { return views.front().camera; }  // the main view's, unjittered
  // Records `pass`'s counter `name` for this frame: a logic_error when the pass does not declare
  // it (so every name a reader can see is in some pass's declaration).
  void report(const Pass& pass, const std::string& name, double value);
  // A counter this frame reported; `fallback` where no pass reported it.
  double counter(const std::string& name, double fallback) const;
  // A counter the caller knows a pass reports (a bug when it is missing).
  double counter(const std::string& name) const;
  // The angle a pixel of `view` subtends, times textureFootprint: primary hits' texture LOD.
  float pixelSpread(const View& view) const;
  bool anyCameraMoved() const;

  // The ray tracer, (re)built for the current frame's geometry on first use in a frame.
  RayTracer& rayTracer();
  // The map resolution of a pass's shadow_map_size and shadow_map_fit: `size`, or with `fit` the
  // smallest power of two at least the larger side of a view where that is more (a map spanning
  // the view then has about a texel per pixel, or more).
  int shadowMapResolution(int size, bool fit) const;
  // The frame's shadow maps at `resolution` (texels a side), drawn on first use and redrawn
  // only for what changed (shadow_maps.h). Every pass of a pipeline that asks for the same
  // resolution shares one set. `wanted`: the lights that need maps (ShadowMaps::update).
  ShadowMaps& shadowMaps(int resolution, const std::vector<uint8_t>* wanted = nullptr);
  // The device's maps at `resolution`, shared the same way, as they are (the GPU passes draw them
  // there: passes/common/gpu_shadow_maps.h).
  ShadowMaps& deviceShadowMaps(int resolution);
  // The maps held at `resolution` (the device's or the CPU's), as they are; null when none.
  const ShadowMaps* heldShadowMaps(int resolution, bool device) const;

  // The buffer bound to `pass`'s output slot, created or reshaped to the slot's extent, kind and
  // channels (contents kept when the shape matches). Extent Any: `width` x `height` given here.
  Buffer& output(const Pass& pass, const std::string& slot, int width = 0, int height = 0);
  // The same buffer, shaped, without the device bookkeeping (deviceOutput's).
  Buffer& shapedOutput(const Pass& pass, const std::string& slot, int width, int height);
  // The same when anything reads the output (see keepAllOutputs), else null, and a value left
  // from an earlier frame is dropped (never shown stale).
  Buffer* outputIfConsumed(const Pass& pass, const std::string& slot);
  // Whether anything reads `pass`'s output slot (always true with keepAllOutputs).
  bool isConsumed(const Pass& pass, const std::string& slot) const;
  // The buffer bound to an input slot (this frame's, checked by the pipeline's validation).
  // input, optionalInput, previous and output reject (logic_error naming the pass and slot) a
  // slot the pass does not declare as such: a misspelt slot never reads as "absent".
  const Buffer& input(const Pass& pass, const std::string& slot) const;
  // Last frame's value of a history input slot; null after a reset or before it exists.
  const Buffer* previous(const Pass& pass, const std::string& slot) const;
  // An optional input: null when no pass produced it this frame.
  const Buffer* optionalInput(const Pass& pass, const std::string& slot) const;
  // A Record output: the typed value `pass` hands on through `slot`, new (value-initialised)
  // each frame.
  template <class T>
  T& outputRecord(const Pass& pass, const std::string& slot) {
    Buffer& b = output(pass, slot);
    b.record = T{};
    return std::any_cast<T&>(b.record);
  }
  // This frame's record on an input slot; null when an optional input is missing or its
  // producer was disabled.
  template <class T>
  const T* inputRecord(const Pass& pass, const std::string& slot) const {
    const Buffer* b = optionalInput(pass, slot);
    return b ? recordOf<T>(*b) : nullptr;
  }
  // Last frame's record on a history input slot; null after a reset or before it exists.
  template <class T>
  const T* previousRecord(const Pass& pass, const std::string& slot) const {
    const Buffer* b = previous(pass, slot);
    return b ? recordOf<T>(*b) : nullptr;
  }
  // GPU passes (Pass::hasGpu): the device address of an input slot's buffer (moved to the device
  // by the pipeline before the pass runs), and of an output slot's (shaped as output() shapes it;
  // its new value is on the device until something on the host reads it).
  uint64_t deviceInput(const Pass& pass, const std::string& slot) const;
  uint64_t deviceOutput(const Pass& pass, const std::string& slot, int width = 0, int height = 0);
  // outputIfConsumed's device side: 0 (and no buffer, on either side) when nothing reads it.
  uint64_t deviceOutputIfConsumed(const Pass& pass, const std::string& slot);
  // Last frame's value of a history input slot on the device (moved there by the pipeline); 0
  // after a reset or before it exists, as previous() gives null.
  uint64_t devicePrevious(const Pass& pass, const std::string& slot) const;
  // By buffer name (tests, AOV writing, the viewer).
  const Buffer& input(const std::string& name) const;
  bool has(const std::string& name) const { return buffers.count(name) != 0; }

 private:
  template <class T>
  static const T* recordOf(const Buffer& b) {
    const T* r = std::any_cast<T>(&b.record);
    TANDEM_ASSERT(r || !b.record.has_value());  // the pipeline checked the record's type
    return r;
  }
  std::unique_ptr<RayTracer> rt_;
  std::map<int, std::unique_ptr<ShadowMaps>> shadowMaps_, deviceShadowMaps_;
};

}  // namespace tandem
