// The default lighting rig, for model files that carry no lights (most OBJ and many glTF files):
// what model viewers do, so a dropped-in model renders lit instead of as a black silhouette.
#pragma once
#include "scene/scene.h"

namespace tandem {

// True when the scene has no lights of its own (lights standing in for emissive meshes aside)
// and no emitter bright enough to light it (mean emitted radiance >= 1 in some channel).
bool needsDefaultLights(const Scene& s);

// Adds a sun and a sky around the view `camera` looks along: a key sun from above the viewer's
// left shoulder (casting shadows), a dimmer bluish sky light from straight above and a weak warm
// fill from the right (neither casting shadows), plus a small ambient sky term when the scene
// has none. Lights are named "default-*"; stats.defaultLightRig records it.
void addDefaultLightRig(Scene& s, const CameraDesc& camera);

}  // namespace tandem
