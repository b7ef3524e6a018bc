// Arguments of rt_whitted.comp (C++ and GLSL): the camera of one view, where its pixels go, and
// the Whitted settings (passes/common/whitted_settings.h).
#ifndef TANDEM_GPU_WHITTED_ARGS_H
#define TANDEM_GPU_WHITTED_ARGS_H
#include "camera_data.h"

#define TD_WHITTED_TEXTURED_SHADOWS 1u
#define TD_WHITTED_SHADE_AT_MAX_DEPTH 2u
// Shadows from the frame's shadow maps (shadow_maps.glsl; the kernel then has their address):
// classified (lit, shadowed, or a ray decides), or the maps' lookups decide every one.
#define TD_WHITTED_CLASSIFIED 4u
#define TD_WHITTED_MAPS 8u

// Counters the kernel adds to (uints): rays traced, then the shadow queries by what decided them.
#define TD_COUNT_RAYS 0
#define TD_COUNT_CULLED 1
#define TD_COUNT_TRACED 2
#define TD_COUNT_SURFACES 3
#define TD_COUNT_LIT 4
#define TD_COUNT_SHADOWED 5
#define TD_COUNT_N 6

struct WhittedArgs {
  TD_ADDR scene, camera, hdr, objectId, counters;
  TD_ADDR shadowMaps;  // GpuShadowMapsHeader (TD_WHITTED_CLASSIFIED, _MAPS), else 0
  TD_INT viewX, viewY, frameWidth, maxDepth;
  TD_FLOAT importanceCutoff, shadowCull;
  TD_UINT flags, pad;
};
#endif
