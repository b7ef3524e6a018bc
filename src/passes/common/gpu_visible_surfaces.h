// The GPU side of VisibleSurfaces (raster_gbuffer, vbuffer_shading): every view rasterized in
// compute into its own visibility buffer, 64 bits a pixel written by atomicMax
// (shaders/raster_triangles.glsl, raster_queue.comp), then each pixel resolved along its camera
// ray (raster_resolve.comp) into G-buffer targets and, for vbuffer_shading, shaded.
#pragma once
#include <cstdint>
#include <string>

#include "pipeline/frame_context.h"
#include "pipeline/pass.h"

namespace tandem {

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
