// The resolution parameters of the frame's shared shadow maps (FrameContext::shadowMaps), offered
// with the same names, bounds and words by every pass that asks for them, since they size one
// set of maps the passes share.
#pragma once
#include "pipeline/pass.h"

namespace tandem {

inline ParamDesc shadowMapSizeParam() {
  return {.name = "shadow_map_size",
          .min = 64,
          .max = 8192,
          .doc =
              "shadow map resolution (a sun's map twice the side, a point light's cube faces "
              "half)"};
}

inline ParamDesc shadowMapFitParam() {
  return {.name = "shadow_map_fit",
          .doc =
              "shadow maps sized to the frame: the smallest power of two at least its larger "
              "side where that is more than shadow_map_size"};
}

}  // namespace tandem
