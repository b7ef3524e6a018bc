// Scene loaders. Each throws InputError naming the file, the field and the problem.
#pragma once
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
