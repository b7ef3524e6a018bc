// The GPU side of VisibleSurfaces (raster_gbuffer, vbuffer_shading): every view rasterized in
// compute into its own visibility buffer, 64 bits a pixel written by atomicMax
// (shaders/raster_triangles.glsl, raster_queue.comp), then each pixel resolved along its camera
// ray (raster_resolve.comp) into G-buffer targets and, for vbuffer_shading, shaded.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/frame_context.h"
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
// Records the compute rasterizer's set-up and large-triangle kernels for one view's RasterArgs
// (at `args`, in this submission's constants, whose queue is `queue`) over `triangles` triangles:
// the visibility buffer, cleared by the caller, holds the nearest key a pixel after it.
void recordRasterizer(GpuFrame& gpu, const RasterQueue& queue, uint64_t args, size_t triangles);

class GpuVisibleSurfaces {
 public:
  // Records, view by view, the rasterization and the resolve into `targets` (the address of a
  // GBufferTargets in this submission's constants; a zero field: not written) and into `hdr`
  // when it is non-zero. After the submission reports `pass`'s parts "visibility" and
  // `resolvePart` and its raster/* counters, as VisibleSurfaces::rasterize does.
  void record(FrameContext& ctx, const Pass& pass, uint64_t targets, uint64_t hdr,
              const char* resolvePart);
};

}  // namespace tandem
