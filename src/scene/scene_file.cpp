// Tandem scene files (JSON): primitives and model files placed with transforms, materials with
// every property of Walewski et al. 2019 Table 1, lights, environment, camera, camera path,
// animation and heuristic parameters. The format is documented in docs/scene-format.md.
#include <algorithm>
#include <filesystem>
#include <map>
#include <system_error>
#include <vector>

#include "core/assets.h"
#include "core/image_io.h"
#include "core/json_fields.h"
#include "scene/builtin_scenes.h"
#include "scene/camera_json.h"
#include "scene/loaders.h"
#include "scene/primitives.h"

namespace tandem {
namespace fs = std::filesystem;

namespace {

struct FileCtx {
  std::string path;
  fs::path dir;
  Scene& scene;
  std::map<std::string, int> materials;  // by name
  std::map<std::string, int> textures;   // by resolved path (+ colour space)
};

std::string resolve(const FileCtx& c, const std::string& p) {
  fs::path q(expandAssetPath(p));
  return (q.is_absolute() ? q : c.dir / q).lexically_normal().string();
}

// A model the scene file refers to (as written there); its errors name the scene file and field
// as well, and a missing third-party asset says how to point Tandem at it.
Scene loadModelFor(const FileCtx& c, const std::string& written, const std::string& field) {
  std::string model = resolve(c, written);
  if (isAssetPath(written) && !fs::exists(model))
    throw InputError(c.path, field,
                     model +
                         ": third-party asset not found (this optional scene needs the "
                         "third-party scenes: set TANDEM_ASSETS to their folder)");
  try {
    return loadSceneByExtension(model);
  } catch (const InputError& e) {
    throw InputError(c.path, field, e.what());
  }
}

int readTexture(FileCtx& c, JsonFields& f, const std::string& key, bool srgb) {
  std::string name = f.string(key, "");
  if (name.empty()) return -1;
  std::string p = resolve(c, name);
  std::string cacheKey = p + (srgb ? "#srgb" : "#linear");
  if (auto it = c.textures.find(cacheKey); it != c.textures.end()) return it->second;
  if (!fs::is_regular_file(p)) f.fail(key, "texture file '" + name + "' not found");
  int id = c.scene.addTexture(textureFromImage(p, loadTextureFile(p), srgb));
  c.textures[cacheKey] = id;
  return id;
}

// A material from JSON; fields not given keep `m`'s values (the defaults, or a base model's
// material being edited).
Material readMaterial(FileCtx& c, const Json& j, const std::string& name, const std::string& where,
                      Material m = {}) {
  JsonFields f(j, c.path, where);
  m.name = name;
  m.emission = f.vec3("emission", m.emission);
  m.ambient = f.vec3("ambient", m.ambient);
  m.diffuse = f.vec3("diffuse", m.diffuse);
  m.diffuseOpacity = f.number("diffuseOpacity", m.diffuseOpacity, 0.0f, 1.0f);
  m.specular = f.vec3("specular", m.specular);
  m.specularExponent = f.number("specularExponent", m.specularExponent, 1.0f, 4096.0f);
  m.reflectivity = f.number("reflectivity", m.reflectivity, 0.0f, 1.0f);
  m.ior = f.number("ior", m.ior, 0.1f, 10.0f);
  m.opacity = f.number("opacity", m.opacity, 0.0f, 1.0f);
  m.transmissionFilter = f.vec3("transmissionFilter", m.transmissionFilter);
  m.tiling = f.vec2("tiling", m.tiling);
  m.offset = f.vec2("offset", m.offset);
  m.castsShadows = f.boolean("castsShadows", m.castsShadows);
  m.doubleSided = f.boolean("doubleSided", m.doubleSided);
  m.alphaMode = f.choice<AlphaMode>(
      "alphaMode", m.alphaMode,
      {{"opaque", AlphaMode::Opaque}, {"mask", AlphaMode::Mask}, {"blend", AlphaMode::Blend}});
  m.alphaCutoff = f.number("alphaCutoff", m.alphaCutoff, 0.0f, 1.0f);
  auto texture = [&](const char* key, bool srgb, int& slot) {
    const int t = readTexture(c, f, key, srgb);
    if (t >= 0) slot = t;
  };
  texture("diffuseMap", true, m.diffuseTexture);
  texture("emissionMap", true, m.emissionTexture);
  texture("specularMap", true, m.specularTexture);
  texture("normalMap", false, m.normalTexture);
  f.finish();
  for (Vec3 v : {m.emission, m.ambient, m.diffuse, m.specular})
    if (v.x < 0 || v.y < 0 || v.z < 0) throw InputError(c.path, where, "colours must be >= 0");
  return m;
}

Transform readTransform(JsonFields& f) {
  Transform t;
  t.position = f.vec3("position", t.position);
  t.rotationDeg = f.vec3("rotation", t.rotationDeg);
  t.scale = f.vec3("scale", t.scale);
  return t;
}

int materialRef(FileCtx& c, JsonFields& f, const std::string& key) {
  if (!f.has(key)) return -1;
  const Json& v = f.raw(key);
  if (v.is_string()) {
    auto it = c.materials.find(v.get<std::string>());
    if (it == c.materials.end()) f.fail(key, "unknown material '" + v.get<std::string>() + "'");
    return it->second;
  }
  return c.scene.addMaterial(readMaterial(c, v, "inline", f.field(key)));
}

// Walewski et al. 2019 Table 3's per-object K (relevancy weight) and E (cost weight).
HeuristicParams readHeuristic(const FileCtx& c, const Json& j, const std::string& where) {
  JsonFields hf(j, c.path, where);
  HeuristicParams h;
  h.K = hf.number("K", 1.0f, 0.0f, 1e6f);
  h.E = hf.number("E", 1.0f, 0.0f, 1e6f);
  hf.finish();
  return h;
}

void readObject(FileCtx& c, const Json& j, size_t index) {
  std::string where = "objects[" + std::to_string(index) + "]";
  JsonFields f(j, c.path, where);
  std::string name = f.string("name", "object" + std::to_string(index));
  int material = materialRef(c, f, "material");
  Transform xf = readTransform(f);
  std::vector<TransformKey> keys;
  if (f.has("animation")) {
    const Json& a = f.raw("animation");
    if (!a.is_array() || a.empty()) f.fail("animation", "expected a non-empty array of keyframes");
    float lastTime = -1e30f;
    for (size_t k = 0; k < a.size(); ++k) {
      JsonFields kf(a[k], c.path, f.field("animation") + "[" + std::to_string(k) + "]");
      TransformKey key;
      key.time = kf.number("time", 0.0f);
      if (key.time < lastTime) kf.fail("time", "keyframes must be sorted by time");
      lastTime = key.time;
      key.transform = readTransform(kf);
      kf.finish();
      keys.push_back(key);
    }
  }
  HeuristicParams h;
  if (f.has("heuristic")) h = readHeuristic(c, f.raw("heuristic"), f.field("heuristic"));
  auto place = [&](size_t firstObject) {
    for (size_t o = firstObject; o < c.scene.objects.size(); ++o) {
      c.scene.objects[o].heuristic = h;
      c.scene.objects[o].animation = keys;
    }
  };
  if (f.has("file")) {
    Scene sub = loadModelFor(c, f.string("file", ""), f.field("file"));
    size_t first = c.scene.objects.size();
    // With animation the keyframes place the model; otherwise the object's transform does.
    c.scene.append(sub, keys.empty() ? xf.matrix() : Mat4(), material);
    // Name model parts after the placing object so that `info` shows where they came from.
    for (size_t o = first; o < c.scene.objects.size(); ++o)
      c.scene.objects[o].name = name + "/" + c.scene.objects[o].name;
    place(first);
    f.finish();
    return;
  }
  std::string shape = f.string("shape", "");
  Mesh mesh;
  if (shape == "plane") {
    mesh = makePlane(f.integer("subdivisions", 1, 1, 1024));
  } else if (shape == "cube") {
    mesh = makeCube();
  } else if (shape == "sphere") {
    int slices = f.integer("slices", 32, 3, 1024);
    int stacks = f.integer("stacks", 16, 2, 1024);
    mesh = makeUvSphere(slices, stacks);
  } else if (shape == "knot") {
    int p = f.integer("p", 2, 1, 16), q = f.integer("q", 3, 1, 16);
    float tube = f.number("tube", 0.45f, 0.01f, 1.0f);
    mesh = makeTorusKnot(p, q, tube, f.integer("segments", 256, 8, 8192),
                         f.integer("sides", 24, 3, 1024));
  } else if (shape.empty()) {
    f.fail("shape", "an object needs \"shape\" (plane, cube, sphere, knot) or \"file\"");
  } else {
    f.fail("shape", "unknown shape '" + shape + "' (plane, cube, sphere, knot)");
  }
  if (material < 0) material = c.scene.addMaterial(Material{});
  int obj = c.scene.addObject(name, c.scene.addMesh(std::move(mesh)), material,
                              keys.empty() ? xf : Transform{});
  place(size_t(obj));
  f.finish();
}

Light readLight(const FileCtx& c, const Json& j, size_t index) {
  JsonFields f(j, c.path, "lights[" + std::to_string(index) + "]");
  Light l;
  const std::string type = f.string("type", "");
  l.type = f.choice<LightType>("type", std::nullopt,
                               {{"directional", LightType::Directional},
                                {"point", LightType::Point},
                                {"spot", LightType::Spot}});
  l.name = f.string("name", type + std::to_string(index));
  l.color = f.vec3("color", l.color);
  l.intensity = f.number("intensity", 1.0f, 0.0f, 1e9f);
  l.position = f.vec3("position", l.position);
  Vec3 d = f.vec3("direction", l.direction);
  if (length(d) == 0) f.fail("direction", "must not be zero");
  l.direction = normalize(d);
  Vec3 att = f.vec3("attenuation", {l.attConstant, l.attLinear, l.attQuadratic});
  if (att.x < 0 || att.y < 0 || att.z < 0 || att.x + att.y + att.z <= 0)
    f.fail("attenuation", "coefficients must be >= 0 and not all zero");
  l.attConstant = att.x;
  l.attLinear = att.y;
  l.attQuadratic = att.z;
  l.range = f.number("range", 0.0f, 0.0f, 1e9f);
  l.innerConeDeg = f.number("innerCone", l.innerConeDeg, 0.0f, 90.0f);
  l.outerConeDeg = f.number("outerCone", l.outerConeDeg, 0.0f, 90.0f);
  if (l.innerConeDeg > l.outerConeDeg) f.fail("innerCone", "must not exceed outerCone");
  l.cosinePower = f.number("cosinePower", 0.0f, 0.0f, 1000.0f);
  l.castsShadows = f.boolean("castsShadows", true);
  f.finish();
  return l;
}

}  // namespace

CameraDesc cameraFromJson(const Json& j, const std::string& file, CameraDesc d) {
  JsonFields f(j, file, "camera");
  d.projection = f.choice<Projection>(
      "projection", Projection::Perspective,
      {{"perspective", Projection::Perspective}, {"orthographic", Projection::Orthographic}});
  d.position = f.vec3("position", d.position);
  d.lookAt = f.vec3("lookAt", d.lookAt);
  d.up = f.vec3("up", d.up);
  if (length(d.lookAt - d.position) == 0) f.fail("lookAt", "must differ from position");
  d.vfovDeg = f.number("vfov", d.vfovDeg, 0.01f, 179.0f);
  d.orthoHeight = f.number("orthoHeight", d.orthoHeight, 1e-6f, 1e9f);
  d.nearPlane = f.number("near", d.nearPlane, 1e-6f, 1e9f);
  d.farPlane = f.number("far", d.farPlane, 1e-6f, 1e12f);
  d.apertureDiameter = f.number("aperture", d.apertureDiameter, 0.0f, 1e3f);
  d.focalLength = f.number("focalLength", d.focalLength, 1e-6f, 1e3f);
  d.focusDistance = f.number("focusDistance", d.focusDistance, 1e-6f, 1e9f);
  d.sensorWidth = f.number("sensorWidth", d.sensorWidth, 1e-6f, 1e3f);
  d.apertureBlades = f.integer("apertureBlades", d.apertureBlades, 0, 64);
  if (d.apertureBlades == 1 || d.apertureBlades == 2)
    f.fail("apertureBlades", "must be 0 (circular) or at least 3");
  d.apertureRotationDeg = f.number("apertureRotation", d.apertureRotationDeg, -360.0f, 360.0f);
  f.finish();
  return d;
}

StereoDesc stereoFromJson(const Json& j, const std::string& file, StereoDesc d) {
  JsonFields f(j, file, "stereo");
  d.enabled = f.boolean("enabled", true);
  d.ipd = f.number("ipd", d.ipd, 1e-6f, 1e3f);
  d.converged = f.boolean("converged", d.converged);
  d.convergence = f.number("convergence", d.convergence, 1e-6f, 1e9f);
  f.finish();
  return d;
}

Json cameraToJson(const CameraDesc& d) {
  auto v = [](Vec3 x) { return Json::array({x.x, x.y, x.z}); };
  Json j = {
      {"projection", d.projection == Projection::Perspective ? "perspective" : "orthographic"},
      {"position", v(d.position)},
      {"lookAt", v(d.lookAt)},
      {"up", v(d.up)},
      {"vfov", d.vfovDeg},
      {"orthoHeight", d.orthoHeight},
      {"near", d.nearPlane},
      {"far", d.farPlane},
      {"aperture", d.apertureDiameter},
      {"focalLength", d.focalLength},
      {"focusDistance", d.focusDistance},
      {"sensorWidth", d.sensorWidth},
      {"apertureBlades", d.apertureBlades},
      {"apertureRotation", d.apertureRotationDeg}};
  return j;
}

std::vector<CameraKey> cameraPathFromJson(const Json& p, const std::string& file,
                                          const CameraDesc& base) {
  if (!p.is_array()) throw InputError(file, "cameraPath", "expected an array of keys");
  std::vector<CameraKey> keys;
  float lastTime = -1e30f;
  for (size_t i = 0; i < p.size(); ++i) {
    JsonFields kf(p[i], file, "cameraPath[" + std::to_string(i) + "]");
    CameraKey k;
    k.time = kf.number("time", 0.0f);
    if (k.time < lastTime) kf.fail("time", "keys must be sorted by time");
    lastTime = k.time;
    k.position = kf.vec3("position", base.position);
    k.lookAt = kf.vec3("lookAt", base.lookAt);
    kf.finish();
    keys.push_back(k);
  }
  return keys;
}

std::vector<GazeKey> gazeTraceFromJson(const Json& p, const std::string& file) {
  if (!p.is_array() || p.empty()) throw InputError(file, "gazeTrace", "expected an array of keys");
  std::vector<GazeKey> keys;
  float lastTime = -1e30f;
  for (size_t i = 0; i < p.size(); ++i) {
    JsonFields kf(p[i], file, "gazeTrace[" + std::to_string(i) + "]");
    GazeKey k;
    k.time = kf.number("time", 0.0f);
    if (k.time < lastTime) kf.fail("time", "keys must be sorted by time");
    lastTime = k.time;
    const Vec2 g = kf.vec2("gaze", k.gaze);
    if (!(g.x >= 0 && g.x <= 1 && g.y >= 0 && g.y <= 1))
      kf.fail("gaze", "must be a fraction of the viewport, in [0, 1]");
    k.gaze = g;
    kf.finish();
    keys.push_back(k);
  }
  return keys;
}

Json cameraPathToJson(const std::vector<CameraKey>& keys) {
  Json a = Json::array();
  for (const CameraKey& k : keys)
    a.push_back({{"time", k.time},
                 {"position", Json::array({k.position.x, k.position.y, k.position.z})},
                 {"lookAt", Json::array({k.lookAt.x, k.lookAt.y, k.lookAt.z})}});
  return a;
}

namespace {

void readCamera(FileCtx& c, const Json& j) {
  c.scene.camera = cameraFromJson(j, c.path, c.scene.camera);
  c.scene.hasCamera = true;
}

void readSkybox(FileCtx& c, const Json& j) {
  JsonFields f(j, c.path, "skybox");
  c.scene.skybox.color = f.vec3("color", c.scene.skybox.color);
  if (f.has("faces")) {
    const Json& faces = f.raw("faces");
    if (!faces.is_array() || faces.size() != 6 ||
        !std::all_of(faces.begin(), faces.end(), [](const Json& v) { return v.is_string(); }))
      f.fail("faces", "expected 6 image paths (+X, -X, +Y, -Y, +Z, -Z)");
    for (int k = 0; k < 6; ++k) {
      std::string p = resolve(c, faces[k].get<std::string>());
      if (!fs::is_regular_file(p))
        f.fail("faces", "image '" + faces[k].get<std::string>() + "' not found");
      c.scene.skybox.faces[k] = c.scene.addTexture(textureFromImage(p, loadTextureFile(p), true));
    }
  }
  f.finish();
}

}  // namespace

Light lightFromJson(const Json& j, const std::string& source, size_t index) {
  Scene unused;
  return readLight(FileCtx{source, fs::path("."), unused, {}, {}}, j, index);
}

namespace {

// The scene files being loaded on this thread, outermost first: a file reached again through
// `base` or an object's `file` is a cycle, and the chain is bounded however it is written.
thread_local std::vector<std::string> tLoading;
constexpr size_t kMaxSceneNesting = 32;

class LoadingFile {
 public:
  explicit LoadingFile(const std::string& path) {
    std::error_code ec;
    fs::path key = fs::weakly_canonical(fs::absolute(path, ec), ec);
    const std::string k = ec ? fs::path(path).lexically_normal().string() : key.string();
    auto chain = [&] {
      std::string s;
      for (const std::string& p : tLoading) s += fs::path(p).filename().string() + " -> ";
      return s + fs::path(path).filename().string();
    };
    if (std::find(tLoading.begin(), tLoading.end(), k) != tLoading.end())
      throw InputError(path, "", "the scene refers to itself (" + chain() + ")");
    if (tLoading.size() >= kMaxSceneNesting)
      throw InputError(path, "",
                       "scene files nest deeper than " + std::to_string(kMaxSceneNesting) + " (" +
                           chain() + ")");
    tLoading.push_back(k);
  }
  ~LoadingFile() { tLoading.pop_back(); }
  LoadingFile(const LoadingFile&) = delete;
  LoadingFile& operator=(const LoadingFile&) = delete;
};

}  // namespace

Scene loadSceneFile(const std::string& path) {
  const LoadingFile guard(path);
  return loadSceneJson(readJsonFile(path), path, fs::path(path).parent_path().string());
}

Scene loadSceneJson(const Json& root, const std::string& path, const std::string& dir) {
  Scene s;
  FileCtx c{path, fs::path(dir), s, {}, {}};
  JsonFields f(root, path, "");
  if (f.has("base")) {
    std::string base = f.string("base", "");
    s = isBuiltinScene(base) ? makeBuiltinScene(base) : loadModelFor(c, base, "base");
    for (size_t i = 0; i < s.materials.size(); ++i) c.materials[s.materials[i].name] = int(i);
  }
  s.name = fs::path(path).stem().string();
  s.stats.sources.push_back(path);
  if (f.has("materialEdits")) {
    // Changes to the base model's materials by name: only the fields given change.
    const Json& edits = f.raw("materialEdits");
    if (!edits.is_object()) f.fail("materialEdits", "expected an object of name -> fields");
    for (auto it = edits.begin(); it != edits.end(); ++it) {
      const std::string where = "materialEdits." + it.key();
      bool found = false;
      for (Material& m : s.materials)
        if (m.name == it.key()) m = readMaterial(c, it.value(), it.key(), where, m), found = true;
      if (!found) throw InputError(path, where, "the base has no material of that name");
    }
  }
  if (f.has("materials")) {
    const Json& mats = f.raw("materials");
    if (!mats.is_object()) f.fail("materials", "expected an object of name -> material");
    for (auto it = mats.begin(); it != mats.end(); ++it)
      c.materials[it.key()] =
          s.addMaterial(readMaterial(c, it.value(), it.key(), "materials." + it.key()));
  }
  if (f.has("objects")) {
    const Json& objs = f.raw("objects");
    if (!objs.is_array()) f.fail("objects", "expected an array");
    for (size_t i = 0; i < objs.size(); ++i) readObject(c, objs[i], i);
  }
  // "baseLights": false drops the base scene's lights (the file's own "lights" replace them).
  if (!f.boolean("baseLights", true)) s.lights.clear();
  if (f.has("lights")) {
    const Json& lights = f.raw("lights");
    if (!lights.is_array()) f.fail("lights", "expected an array");
    for (size_t i = 0; i < lights.size(); ++i) s.lights.push_back(readLight(c, lights[i], i));
  }
  if (f.has("objectHeuristics")) {
    // K and E for objects that came from `base` or a model file, by object name.
    const Json& oh = f.raw("objectHeuristics");
    if (!oh.is_object()) f.fail("objectHeuristics", "expected an object of object name -> {K, E}");
    for (auto it = oh.begin(); it != oh.end(); ++it) {
      std::string where = "objectHeuristics." + it.key();
      HeuristicParams h = readHeuristic(c, it.value(), where);
      bool found = false;
      for (Object& o : s.objects)
        if (o.name == it.key()) {
          o.heuristic = h;
          found = true;
        }
      if (!found) throw InputError(path, where, "no object of that name in the scene");
    }
  }
  s.ambient = f.vec3("ambient", s.ambient);
  s.environmentIor = f.number("environmentIor", s.environmentIor, 0.1f, 10.0f);
  if (f.has("skybox")) readSkybox(c, f.raw("skybox"));
  if (f.has("camera")) readCamera(c, f.raw("camera"));
  if (f.has("cameraPath")) s.cameraPath = cameraPathFromJson(f.raw("cameraPath"), path, s.camera);
  if (f.has("stereo")) s.stereo = stereoFromJson(f.raw("stereo"), path, s.stereo);
  if (f.has("gazeTrace")) s.gazeTrace = gazeTraceFromJson(f.raw("gazeTrace"), path);
  f.finish();
  if (s.objects.empty()) throw InputError(path, "objects", "scene has no objects");
  validateScene(s, path);
  return s;
}

Scene loadSceneByExtension(const std::string& path) {
  if (hasExtension(path, ".obj")) return loadObj(path);
  if (hasExtension(path, ".gltf") || hasExtension(path, ".glb")) return loadGltf(path);
  if (hasExtension(path, ".json")) return loadSceneFile(path);
  throw InputError(path, "", "unknown scene format (expected .gltf, .glb, .obj or .json)");
}

Scene loadScene(const std::string& pathOrName, const LoadOptions& opts) {
  Scene s;
  if (isBuiltinScene(pathOrName) && !fs::exists(pathOrName)) {
    s = makeBuiltinScene(pathOrName);
  } else if (!fs::exists(pathOrName) && pathOrName.find('.') == std::string::npos &&
             pathOrName.find('/') == std::string::npos) {
    throw InputError(pathOrName, "scene",
                     "not a file and not a built-in scene (cornell, spheres, atrium)");
  } else {
    s = loadSceneByExtension(pathOrName);
  }
  bool hasPunctual = !s.lights.empty();
  if (opts.emissiveLights == LoadOptions::EmissiveLights::On ||
      (opts.emissiveLights == LoadOptions::EmissiveLights::Auto && !hasPunctual))
    addLightsForEmissiveMeshes(s);
  return s;
}

}  // namespace tandem
