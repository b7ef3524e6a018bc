// The frame's raster shadow maps on the device (shaders/shadow_maps_data.h): the maps are drawn
// by the CPU rasterizer (ShadowMaps::update: the static casters once, animated ones when they
// moved) and copied to the device whenever they were redrawn, so classified and shadow-map
// shadows are decided in the kernels (shaders/shadow_maps.glsl).
#pragma once
#include <cstdint>
#include <vector>

#include "raster/shadow_maps.h"

namespace tandem {

class FrameContext;
class Pass;

// The device address of `maps` as shadow_maps.glsl reads it, uploaded first when they changed
// (a timing part "shadow_maps_upload" with its bytes).
uint64_t gpuShadowMaps(FrameContext& ctx, const ShadowMaps& maps);

// lightsInView on the device: records shaders/lights_in_view.comp over the frame's views (from
// `pass`'s G-buffer sample slots). The result is the lights' flags, read with wantedLights once
// the caller's next checkpoint has run them.
const uint32_t* recordLightsInView(FrameContext& ctx, const Pass& pass);
std::vector<uint8_t> wantedLights(const uint32_t* flags, size_t lights);

}  // namespace tandem
