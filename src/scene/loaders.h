// Scene loaders. Each throws InputError naming the file, the field and the problem.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "scene/scene.h"

namespace tandem {

struct LoadOptions {
  // Emissive meshes become equivalent punctual lights: Auto converts only when the scene has
  // no punctual lights of its own, so pipelines without area lights still see light.
  enum class EmissiveLights { Auto, On, Off } emissiveLights = EmissiveLights::Auto;
};

Scene loadObj(const std::string& path);
Scene loadGltf(const std::string& path);
Scene loadSceneFile(const std::string& path);  // Tandem JSON
// A Tandem scene given as JSON text's parsed object (from Python, say): `source` names it in
// errors and is its name, `dir` is where relative paths start.
Scene loadSceneJson(const nlohmann::json& root, const std::string& source, const std::string& dir);

// One entry of a scene file's "lights" (docs/scene-format.md); errors name `source` and
// lights[index].
Light lightFromJson(const nlohmann::json& j, const std::string& source, size_t index);

// A `.gltf`/`.glb`/`.obj`/`.json` path or a built-in name; applies LoadOptions afterwards.
Scene loadScene(const std::string& pathOrName, const LoadOptions& opts = {});
// Loads OBJ/glTF/JSON by extension, without post-processing (used by scene files).
Scene loadSceneByExtension(const std::string& path);

// Emissive-mesh conversion (documented in docs/scene-format.md): a planar emitter becomes a
// spot light with cosine falloff I(theta) = Le * A * cos(theta) over the hemisphere; any other
// emitter becomes a point light of the same power, I = Le * A / 4. Le is the emission factor
// times the emission texture's mean colour. Returns lights added.
int addLightsForEmissiveMeshes(Scene& s);
// A material's emitted radiance averaged over its emission texture (the factor when untextured).
Vec3 meanEmission(const Scene& s, const Material& m);

}  // namespace tandem
