// The frame's raster shadow maps on the device (shaders/shadow_maps_data.h): the maps are drawn
// by the CPU rasterizer (ShadowMaps::update: the static casters once, animated ones when they
// moved) and copied to the device whenever they were redrawn, so classified and shadow-map
// shadows are decided in the kernels (shaders/shadow_maps.glsl).
#pragma once
#include <cstdint>

#include "raster/shadow_maps.h"

namespace tandem {

class FrameContext;

// The device address of `maps` as shadow_maps.glsl reads it, uploaded first when they changed
// (a timing part "shadow_maps_upload" with its bytes).
uint64_t gpuShadowMaps(FrameContext& ctx, const ShadowMaps& maps);

}  // namespace tandem
