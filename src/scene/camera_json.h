// Cameras and camera paths in the scene file format (docs/scene-format.md), both ways: the
// scene loader reads them, the viewer saves and loads views and recorded paths with them.
#pragma once
#include <string>
#include <vector>

#include "core/json_fields.h"
#include "scene/animation.h"
#include "scene/camera.h"

namespace tandem {

// Fields absent from `j` keep `base`'s values; throws InputError naming file and field.
CameraDesc cameraFromJson(const Json& j, const std::string& file, CameraDesc base = {});
// "stereo": {"enabled" (default true), "ipd", "converged", "convergence"}.
StereoDesc stereoFromJson(const Json& j, const std::string& file, StereoDesc base = {});
Json cameraToJson(const CameraDesc& c);
std::vector<CameraKey> cameraPathFromJson(const Json& j, const std::string& file,
                                          const CameraDesc& base);
Json cameraPathToJson(const std::vector<CameraKey>& keys);

}  // namespace tandem
