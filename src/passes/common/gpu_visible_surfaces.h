// The GPU side of VisibleSurfaces (raster_gbuffer, vbuffer_shading): every view rasterized in
// compute into its own visibility buffer, 64 bits a pixel written by atomicMax
// (shaders/raster_triangles.glsl, raster_queue.comp), then each pixel resolved along its camera
// ray (raster_resolve.comp) into G-buffer targets and, for vbuffer_shading, shaded.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/frame_context.h"
#include "pipeline/param_table.h"
#include "pipeline/pass.h"

namespace tandem {

class GpuFrame;
struct GpuBuffer;

// The objects with draw[o] != 0 as the rasterizer's spans (raster_args.h RasterSpan), in this
// submission's constants: their address and count, the triangles they hold.
struct RasterSpans {
  uint64_t address = 0;
  uint32_t count = 0;
  size_t triangles = 0;
};
RasterSpans rasterSpans(GpuFrame& gpu, const Scene& scene, const std::vector<uint32_t>& draw);

// The compute rasterizer's queue of large triangles, kept as scratch `key` for up to `triangles`.
struct RasterQueue {
  const GpuBuffer* buffer;
  uint32_t capacity;
};
RasterQueue rasterQueue(GpuFrame& gpu, const std::string& key, size_t triangles);
// One view for the compute rasterizer: the objects drawn (draw[o] != 0), the camera (its pixel
// rays test alpha masks at `pixelSpread`'s texture level), the visibility buffer drawn into
// (cleared, or holding what the view is drawn over).
// Sample mode (interleaved sampling): one pass's samples, on the device (raster_args.h): the
// visibility buffer is then indexed by sample id.
struct RasterSamples {
  uint64_t start = 0, ids = 0, fixedPos = 0, pos = 0;
  int cellW = 1, cellH = 1, cellsX = 0, cellsY = 0;
};
struct RasterView {
  const Camera* camera = nullptr;
  float pixelSpread = 0;
  const std::vector<uint32_t>* draw = nullptr;
  const GpuBuffer* visibility = nullptr;
  bool bothFaces = false;
  const RasterSamples* samples = nullptr;  // null: every pixel centre
  float tau = 0;  // the shutter fraction moving objects are drawn at (their time steps)
};
// Records the compute rasterizer's set-up and large-triangle kernels for `view` over the drawn
// objects' triangles, with `queue`: afterwards each pixel of the visibility buffer holds the
// nearest key. The address of its counters (TD_RASTER_COUNT_N uints, read after the submission).
uint64_t recordRasterizer(GpuFrame& gpu, const Scene& scene, uint64_t sceneAddress,
                          const RasterQueue& queue, const RasterView& view);

// The setting of the passes that rasterize the frame (raster_gbuffer, vbuffer_shading): on the
// GPU, the compute rasterizer (the CPU's coverage and depths) or the graphics pipeline's hardware
// rasterizer, to time one against the other. The CPU ignores it.
struct RasterizerSettings {
  enum class GpuRasterizer { Compute, Graphics };
  GpuRasterizer gpuRasterizer = GpuRasterizer::Compute;
};
const ParamTable<RasterizerSettings>& rasterizerTable();

class GpuVisibleSurfaces {
 public:
  // Records, view by view, the rasterization and the resolve into `targets` (the address of a
  // GBufferTargets in this submission's constants; a zero field: not written) and into `hdr`
  // when it is non-zero. After the submission reports `pass`'s parts "visibility" and
  // `resolvePart` and its raster/* counters, as VisibleSurfaces::rasterize does. `graphics`: the
  // visibility drawn by the graphics pipeline (gpu_graphics_raster.h) instead, whose hardware
  // counts nothing: only the triangles in and those of objects outside the frustum are reported.
  void record(FrameContext& ctx, const Pass& pass, uint64_t targets, uint64_t hdr,
              const char* resolvePart, bool graphics = false);
};

}  // namespace tandem
