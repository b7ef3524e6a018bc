// Arguments of blend.comp (C++ and GLSL): the lighting, the three traced effects, the G-buffer's
// optical target, the heuristic mask and ss_fallback's buffer (0: none), and the composite.
#ifndef TANDEM_GPU_BLEND_ARGS_H
#define TANDEM_GPU_BLEND_ARGS_H
#include "shared.h"

// ss_fallback's `fallback` buffer (passes/heuristic/effect_channels.h): 11 floats a pixel.
#define TD_FALLBACK_REFLECTION 0
#define TD_FALLBACK_REFRACTION 3
#define TD_FALLBACK_SHADOW 6
#define TD_FALLBACK_COVERS_EFFECT 9
#define TD_FALLBACK_COVERS_SHADOW 10
#define TD_FALLBACK_CHANNELS 11

struct BlendArgs {
  TD_ADDR hdr, shadow, reflection, refraction, optical, mask, fallback, composite;
  TD_UINT width, height;
};
#endif
