// The scene: meshes, objects (a mesh placed with a material and a transform, possibly animated),
// materials, textures, lights, camera and environment. Loaders and built-in generators all
// produce this; the rasterizer and the ray tracer both read the FrameScene evaluated from it.
#pragma once
#include <string>
#include <vector>

#include "scene/animation.h"
#include "scene/camera.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/mesh.h"
#include "scene/texture.h"

namespace tandem {

struct HeuristicParams {
  float K = 1.0f;  // static relevancy (Walewski et al. 2019 Table 3)
  float E = 1.0f;  // estimated cost of the object's effects
};

struct Object {
  std::string name;
  int mesh = 0;
  int material = 0;
  // world(t) = animation(t) * parent * local: `local` places a primitive, `parent` carries a
  // model file's node chain and placement, `animation` (when keyed) moves the whole object.
  Mat4 parent;
  Transform local;
  std::vector<TransformKey> animation;
  HeuristicParams heuristic;

  Mat4 worldMatrix(float t) const {
    Mat4 m = parent * local.matrix();
    return animation.empty() ? m : sampleTransform(animation, t).matrix() * m;
  }
  bool animated() const { return animation.size() > 1; }
};

struct Skybox {
  Vec3 color{0.05f, 0.05f, 0.05f};          // used when no faces are given (linear)
  int faces[6] = {-1, -1, -1, -1, -1, -1};  // textures for +X, -X, +Y, -Y, +Z, -Z
  bool hasFaces() const { return faces[0] >= 0; }
};

struct LoadStats {
  size_t degenerateTriangles = 0;    // skipped while loading
  std::vector<std::string> sources;  // files this scene was built from
  size_t skippedPrimitives = 0;      // glTF points and lines (nothing to shade)
  bool defaultLightRig = false;      // lit by addDefaultLightRig (the file has no lights)
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Object> objects;
  std::vector<Light> lights;
  Vec3 ambient{0.0f, 0.0f, 0.0f};  // global ambient colour (Listing 5)
  float environmentIor = 1.0f;
  Skybox skybox;
  CameraDesc camera;
  bool hasCamera = false;
  StereoDesc stereo;  // scene file "stereo": {"ipd", "converged", "convergence"}; --stereo
  std::vector<CameraKey> cameraPath;
  std::vector<GazeKey> gazeTrace;  // scene file "gazeTrace": where the viewer looks over time
  LoadStats stats;

  size_t triangleCount() const;
  Bounds3 bounds(float t = 0.0f) const;
  size_t memoryBytes() const;
  Vec3 skyRadiance(Vec3 dir) const;

  // Appends another scene's content (meshes, materials, textures re-indexed), with `xf` applied
  // to its objects and lights. Used by scene files that place models into a scene.
  void append(const Scene& other, const Mat4& xf, int materialOverride = -1);
  int addMaterial(const Material& m);
  int addTexture(Texture t);
  int addMesh(Mesh m);
  int addObject(std::string name, int mesh, int material, Transform xf = {});
};

// Checks internal consistency after loading (indices in range, finite vertices, unit normals):
// throws InputError naming `source` on violation. Loaders call it; bugs cannot slip past it.
void validateScene(const Scene& s, const std::string& source);

}  // namespace tandem
