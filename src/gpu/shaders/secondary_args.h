// Arguments of rt_secondary.comp (C++ and GLSL): the G-buffer it starts from, the heuristic mask,
// where the three effects go, and the Whitted settings (passes/common/whitted_settings.h).
#ifndef TANDEM_GPU_SECONDARY_ARGS_H
#define TANDEM_GPU_SECONDARY_ARGS_H
#include "whitted_args.h"

// Per object, rt_stats' tallies (uints): pixels of each effect, then rays of each effect.
#define TD_STATS_PER_OBJECT 6

struct SecondaryArgs {
  TD_ADDR scene, view, sources, mask;  // sources: GBufferTargets (the sample slots)
  TD_ADDR shadow, reflection, refraction, traced, shadowClass;  // shadowClass 0: not read
  // TD_COUNT_N uints, then per object TD_STATS_PER_OBJECT uints
  TD_ADDR counters;
  TD_ADDR shadowMaps;  // GpuShadowMapsHeader (TD_WHITTED_CLASSIFIED, _MAPS), else 0
  TD_INT viewX, viewY, frameWidth, maxDepth;
  TD_FLOAT importanceCutoff, shadowCull, outsideShadow;
  TD_UINT flags;  // TD_WHITTED_*
  TD_INT classLight, pad;
};
#endif
