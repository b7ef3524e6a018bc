// A scene made to exercise every material feature the GPU's surface resolve ports (texture wraps
// and mip levels, UV transforms, alpha masks and blending, normal maps, metallic-roughness,
// emission, occlusion and specular textures, transmission filters, spot/point/directional
// lights with ranges, a light casting no shadows, an object casting none, a cube-map sky), and a
// camera that sees all of it.
#pragma once
#include "scene/scene.h"

namespace tandem {

Scene featureScene();
CameraDesc featureCamera();

}  // namespace tandem
