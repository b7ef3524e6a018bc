// The frame's raster shadow maps on the device (shaders/shadow_maps_data.h). ShadowMaps plans what
// to draw as it does for the CPU's maps (the static casters once, animated ones where they moved,
// lights as they come into view); the device draws it into buffers it keeps: the depth maps with
// the compute rasterizer (both faces), the conservative maps with conservative_depth.comp, the
// opaque casters' depth with shadow_map_texels.comp. Classified and shadow-map shadows are then
// decided in the kernels (shaders/shadow_maps.glsl), and nothing is drawn or copied by the host.
#pragma once
#include <cstdint>
#include <vector>

#include "raster/shadow_maps.h"

namespace tandem {

class FrameContext;
class Pass;

// The frame's maps at `resolution` on the device, brought up to date for the `wanted` lights
// (ShadowMaps::update) by commands recorded into the current submission, ahead of the caller's
// kernels; their GPU time is `pass`'s part "shadow_maps".
const ShadowMaps& deviceShadowMaps(FrameContext& ctx, const Pass& pass, int resolution,
                                   const std::vector<uint8_t>* wanted);
// The address of device maps' records (GpuShadowMapsHeader) for this submission's kernels.
uint64_t gpuShadowMaps(FrameContext& ctx, const ShadowMaps& maps);

// One face of device maps as the device holds it, read back (tests): the depth map (reversed Z),
// the conservative map, the opaque casters' depth, as ShadowMaps::FaceView shows the CPU's.
struct DeviceShadowFace {
  int width = 0, height = 0;
  std::vector<float> depth;
  std::vector<ConservativeDepth::Texel> near;
  std::vector<float> opaque;
};
DeviceShadowFace readDeviceShadowFace(const ShadowMaps& maps, size_t light, size_t face);

// lightsInView on the device: records shaders/lights_in_view.comp over the frame's views (from
// `pass`'s G-buffer sample slots). The result is the lights' flags, read with wantedLights once
// the caller's next checkpoint has run them.
const uint32_t* recordLightsInView(FrameContext& ctx, const Pass& pass);
std::vector<uint8_t> wantedLights(const uint32_t* flags, size_t lights);

}  // namespace tandem
