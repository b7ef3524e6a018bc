// Which lights reach a surface the frame shows: the only lights whose shadow maps the hybrid's
// classified and fallback shadows, which shade G-buffer pixels alone, can ask about. A scene of
// many ranged lights then draws maps for the lights around the view, not for all of them.
#pragma once
#include <cstdint>
#include <vector>

#include "scene/view.h"
#include "shading/blinn_phong.h"
#include "shading/gbuffer_sample.h"

namespace tandem {

// Per light, 1 when it may light a surface in the G-buffer (lightsReaching over the box of each
// view tile's positions; a superset of the lights any pixel's shading evaluates), else 0.
std::vector<uint8_t> lightsInView(const std::vector<View>& views, const GBufferReader& g,
                                  const ShadingContext& shading);

}  // namespace tandem
