// Reflection probes on the device: ReflectionProbes chooses which to draw as it does on the CPU
// (missing ones now, outdated ones a few a frame, the least wanted freed); each face is drawn by
// the compute rasterizer (the object left out, as on the CPU) and resolved and shaded into device
// memory by raster_resolve.comp (unshadowed, the sky behind), where fallback.comp looks it up.
// Nothing is drawn or copied by the host.
#pragma once
#include <cstdint>

#include "passes/heuristic/reflection_probes.h"

namespace tandem {

class FrameContext;

// Makes `probes` the device's (on first use, and with every probe to draw anew when the device
// lost them) and records into the current submission whatever its next update() draws.
void drawProbesOnDevice(FrameContext& ctx, ReflectionProbes& probes);
// The probes as fallback.comp reads them: a GpuProbe per object, for this submission's kernels.
uint64_t gpuProbes(FrameContext& ctx, const ReflectionProbes& probes);

}  // namespace tandem
