#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "core/image_io.h"
#include "scene/builtin_scenes.h"
#include "scene/loaders.h"
#include "test_util.h"

using namespace tandem;
using tandem::test::scratchDir;
using tandem::test::writeText;

TEST(ObjLoader, CornellBoxOriginal) {
  TANDEM_ASSET(cornellObj, "CornellBox/CornellBox-Original.obj");
  Scene s = loadObj(cornellObj);
  EXPECT_EQ(s.triangleCount(), 36u);
  EXPECT_GE(s.objects.size(), 8u);
  // The light's MTL Ke = (17, 12, 4) becomes the material's emission.
  bool found = false;
  for (const Object& o : s.objects)
    if (s.materials[o.material].emission.x == 17.0f) found = true;
  EXPECT_TRUE(found);
  Bounds3 b = s.bounds();
  EXPECT_NEAR(b.hi.y, 1.99f, 0.02f);
}

TEST(ObjLoader, IllumAndIorMapToOpticalProperties) {
  TANDEM_ASSET(cornellSphereObj, "CornellBox/CornellBox-Sphere.obj");
  Scene s = loadObj(cornellSphereObj);
  const Material *mirror = nullptr, *glass = nullptr;
  for (const Material& m : s.materials) {
    if (m.name == "leftSphere") mirror = &m;
    if (m.name == "rightSphere") glass = &m;
  }
  ASSERT_TRUE(mirror && glass);
  EXPECT_EQ(mirror->reflectivity, 1.0f);  // illum 5
  EXPECT_EQ(glass->opacity, 0.0f);        // illum 7
  EXPECT_FLOAT_EQ(glass->ior, 2.5f);      // Ni 2.5
  // illum 7 reflects by Fresnel: Ks times Schlick's F0 = ((2.5 - 1) / (2.5 + 1))^2.
  EXPECT_NEAR(glass->reflectivity, 0.3f * (1.5f / 3.5f) * (1.5f / 3.5f), 1e-6f);
  EXPECT_FLOAT_EQ(glass->transmissionFilter.y, 0.1f);  // Tf 0.1
  EXPECT_EQ(mirror->transmissionFilter.x, 1.0f);       // no Tf: nothing filtered
}

TEST(SceneFile, MaterialEditsChangeOnlyTheGivenFieldsOfBaseMaterials) {
  TANDEM_ASSET(cornellSphereObj, "CornellBox/CornellBox-Sphere.obj");
  // cornell_spheres_obj.json clears the glass sphere of the original Cornell box OBJ.
  Scene s = loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/cornell_spheres_obj.json");
  const Material* glass = nullptr;
  for (const Material& m : s.materials)
    if (m.name == "rightSphere") glass = &m;
  ASSERT_TRUE(glass);
  EXPECT_EQ(glass->transmissionFilter.x, 1.0f);
  EXPECT_EQ(glass->reflectivity, 0.0f);
  EXPECT_FLOAT_EQ(glass->ior, 2.5f);  // untouched fields stay the MTL's
  EXPECT_EQ(glass->opacity, 0.0f);
  auto dir = test::scratchDir("material_edits");
  writeText(dir / "bad.json", R"({"base": ")" + cornellSphereObj +
                                  R"(", "materialEdits": {"noSuchMaterial": {"ior": 1.2}}})");
  try {
    loadScene((dir / "bad.json").string());
    FAIL() << "an edit of a missing material loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("materialEdits.noSuchMaterial"), std::string::npos);
  }
}

TEST(EmissiveLights, CornellLightBecomesCosineSpotWithKeTimesArea) {
  TANDEM_ASSET(cornellObj, "CornellBox/CornellBox-Original.obj");
  Scene s = loadScene(cornellObj);
  ASSERT_EQ(s.lights.size(), 1u);
  const Light& l = s.lights[0];
  EXPECT_EQ(l.type, LightType::Spot);
  EXPECT_EQ(l.cosinePower, 1.0f);
  EXPECT_NEAR(l.direction.y, -1.0f, 1e-3f);  // faces down into the box
  // The light quad is about 0.47 x 0.38 m (scene README: area 0.1786), Ke max = 17.
  EXPECT_NEAR(l.intensity, 17.0f * 0.1786f, 0.05f * 17.0f * 0.1786f);
  EXPECT_NEAR(l.position.y, 1.98f, 0.02f);
  // Turned off on request.
  Scene off = loadScene(cornellObj, {LoadOptions::EmissiveLights::Off});
  EXPECT_TRUE(off.lights.empty());
}

TEST(ObjLoader, BunnyWithoutNormalsGetsSmoothNormals) {
  TANDEM_ASSET(bunnyObj, "StanfordBunny/bunny.obj");
  Scene s = loadObj(bunnyObj);
  EXPECT_EQ(s.triangleCount() + s.stats.degenerateTriangles, 69451u);
  const Mesh& m = s.meshes[s.objects[0].mesh];
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (size_t i = 0; i < m.normals.size(); i += 997) EXPECT_NEAR(length(m.normals[i]), 1.0f, 1e-4f);
}

TEST(GltfLoader, WaterBottleHasTexturesAndNodeRotation) {
  TANDEM_ASSET(waterBottle, "WaterBottle/glTF/WaterBottle.gltf");
  Scene s = loadGltf(waterBottle);
  EXPECT_EQ(s.triangleCount(), 4510u);  // scene README
  ASSERT_EQ(s.objects.size(), 1u);
  const Material& m = s.materials[s.objects[0].material];
  EXPECT_GE(m.diffuseTexture, 0);
  EXPECT_GE(m.normalTexture, 0);
  EXPECT_GE(m.emissionTexture, 0);
  EXPECT_GE(m.metallicRoughnessTexture, 0);
  // The node's 180 degree rotation about Y maps +X to -X.
  Vec3 x = s.objects[0].worldMatrix(0).transformVector({1, 0, 0});
  EXPECT_NEAR(x.x, -1.0f, 1e-5f);
  const Mesh& mesh = s.meshes[s.objects[0].mesh];
  EXPECT_EQ(mesh.tangents.size(), mesh.positions.size());
}

TEST(Material, MetallicRoughnessMapping) {
  // Dielectric: all base colour is diffuse, F0 = 0.04; metal: no diffuse, specular = base.
  BlinnPhongTerms d = fromMetallicRoughness({0.5f, 0.2f, 0.1f}, 0.0f, 1.0f);
  EXPECT_EQ(d.diffuse.x, 0.5f);
  EXPECT_NEAR(d.specular.y, 0.04f, 1e-7f);
  EXPECT_EQ(d.exponent, 1.0f);  // 2 / 1 - 2 = 0, clamped to 1
  EXPECT_EQ(d.reflectivity, 0.0f);
  BlinnPhongTerms m = fromMetallicRoughness({0.9f, 0.6f, 0.2f}, 1.0f, 0.5f);
  EXPECT_EQ(m.diffuse.x, 0.0f);
  EXPECT_NEAR(m.specular.y, 0.6f, 1e-6f);
  EXPECT_NEAR(m.exponent, 2.0f / (0.25f * 0.25f) - 2.0f, 1e-3f);  // alpha = r^2 = 0.25 -> 30
  EXPECT_NEAR(m.reflectivity, 0.5f, 1e-6f);
}

TEST(GltfLoader, SuzanneMetallicRoughnessMapping) {
  TANDEM_ASSET(suzanne, "Suzanne/glTF/Suzanne.gltf");
  Scene s = loadGltf(suzanne);
  EXPECT_EQ(s.triangleCount(), 3936u);
  const Material& m = s.materials[s.objects[0].material];
  EXPECT_GE(m.diffuseTexture, 0);
  EXPECT_GE(m.specularExponent, 1.0f);
}

// A hand-written glTF exercising lights, camera, KHR extensions and sampler modes.
TEST(GltfLoader, ExtensionsLightsAndCamera) {
  auto dir = scratchDir("gltf_ext");
  // One triangle; buffer as base64 data URI: 3 float3 positions (36 bytes).
  const char* b64 = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
  std::string gltf = std::string(R"({
 "asset": {"version": "2.0"},
 "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"],
 "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "spot", "intensity": 5, "color": [1, 0.5, 0.25], "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}},
    {"type": "directional", "intensity": 2}]}},
 "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3]}],
 "nodes": [
   {"mesh": 0, "translation": [1, 0, 0]},
   {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 3, 0]},
   {"extensions": {"KHR_lights_punctual": {"light": 1}}},
   {"camera": 0, "translation": [0, 0, 5]}],
 "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.05}}],
 "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1], "metallicFactor": 0, "roughnessFactor": 0.5},
   "emissiveFactor": [1, 1, 1], "alphaMode": "BLEND",
   "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.75}, "KHR_materials_ior": {"ior": 1.33},
                  "KHR_materials_emissive_strength": {"emissiveStrength": 4}}}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)") +
                     b64 + R"("}]
})";
  writeText(dir / "t.gltf", gltf);
  Scene s = loadGltf((dir / "t.gltf").string());
  ASSERT_EQ(s.objects.size(), 1u);
  const Material& m = s.materials[s.objects[0].material];
  EXPECT_NEAR(m.ior, 1.33f, 1e-6f);
  EXPECT_NEAR(m.opacity, 0.25f, 1e-6f);
  EXPECT_NEAR(m.emission.x, 4.0f, 1e-6f);
  EXPECT_EQ(m.alphaMode, AlphaMode::Blend);
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, LightType::Spot);
  EXPECT_NEAR(s.lights[0].position.y, 3.0f, 1e-6f);
  EXPECT_NEAR(s.lights[0].outerConeDeg, degrees(0.4f), 1e-4f);
  EXPECT_NEAR(s.lights[1].direction.z, -1.0f, 1e-6f);  // default -Z
  EXPECT_TRUE(s.hasCamera);
  EXPECT_NEAR(s.camera.vfovDeg, degrees(0.5f), 1e-4f);
  EXPECT_NEAR(s.camera.position.z, 5.0f, 1e-6f);
  EXPECT_NEAR(s.objects[0].worldMatrix(0).transformPoint({0, 0, 0}).x, 1.0f, 1e-6f);
}

// A tetrahedron as an OBJ file, for scene files that place a model.
std::string writeTetrahedronObj(const std::filesystem::path& dir) {
  writeText(dir / "tet.obj",
            "o tet\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  return (dir / "tet.obj").string();
}

TEST(SceneFile, PrimitivesMaterialsLightsCameraAnimation) {
  auto dir = scratchDir("scene_file");
  const std::string model = writeTetrahedronObj(dir);
  writeText(dir / "s.json", R"({
  "materials": {"red": {"diffuse": [0.8, 0.1, 0.1], "specular": [0.5, 0.5, 0.5], "specularExponent": 64,
                        "reflectivity": 0.3, "ior": 1.4, "opacity": 0.5, "tiling": [2, 3], "offset": [0.1, 0.2],
                        "castsShadows": false, "emission": [0, 0, 0], "ambient": [0.1, 0.1, 0.1], "diffuseOpacity": 0.9}},
  "objects": [
    {"name": "ball", "shape": "sphere", "slices": 12, "stacks": 6, "material": "red", "position": [0, 1, 0],
     "heuristic": {"K": 2.5, "E": 3}},
    {"name": "floor", "shape": "plane", "scale": [5, 1, 5]},
    {"name": "box", "shape": "cube", "animation": [{"time": 0, "position": [0, 0, 0]}, {"time": 1, "position": [2, 0, 0]}]},
    {"name": "model", "file": ")" +
                                model + R"(", "scale": [2, 2, 2], "material": "red"}
  ],
  "lights": [{"type": "point", "position": [0, 4, 0], "intensity": 20},
             {"type": "spot", "position": [0, 4, 0], "direction": [0, -1, 0], "innerCone": 10, "outerCone": 20},
             {"type": "directional", "direction": [0, -1, 0], "intensity": 2}],
  "ambient": [0.05, 0.05, 0.05], "environmentIor": 1.0, "skybox": {"color": [0.2, 0.3, 0.4]},
  "camera": {"position": [0, 2, 6], "lookAt": [0, 1, 0], "vfov": 50, "aperture": 0.02, "focalLength": 0.05,
             "focusDistance": 6, "sensorWidth": 0.036},
  "cameraPath": [{"time": 0, "position": [0, 2, 6], "lookAt": [0, 1, 0]}, {"time": 2, "position": [2, 2, 6], "lookAt": [0, 1, 0]}]
})");
  Scene s = loadSceneFile((dir / "s.json").string());
  ASSERT_EQ(s.objects.size(), 4u);
  EXPECT_EQ(s.meshes[s.objects[0].mesh].triangleCount(), size_t(12 * (6 - 1) * 2 - 12 * 0));
  EXPECT_EQ(s.objects[0].heuristic.K, 2.5f);
  EXPECT_EQ(s.objects[0].heuristic.E, 3.0f);
  const Material& red = s.materials[s.objects[0].material];
  EXPECT_FALSE(red.castsShadows);
  EXPECT_EQ(red.tiling.y, 3.0f);
  EXPECT_NEAR(s.objects[2].worldMatrix(0.5f).transformPoint({0, 0, 0}).x, 1.0f, 1e-6f);
  EXPECT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.camera.apertureDiameter, 0.02f);
  EXPECT_EQ(s.cameraPath.size(), 2u);
  EXPECT_NEAR(s.objects[3].worldMatrix(0).m[0][0], 2.0f, 1e-6f);
  EXPECT_EQ(s.objects[3].material, s.objects[0].material);
}

TEST(SceneFile, BaseBuiltinPlusModel) {
  auto dir = scratchDir("scene_base");
  writeText(dir / "s.json", R"({"base": "cornell", "objects": [{"file": ")" +
                                writeTetrahedronObj(dir) +
                                R"(", "material": "glass", "position": [0, 0, 0]}]})");
  Scene s = loadSceneFile((dir / "s.json").string());
  Scene base = makeCornellScene();
  EXPECT_EQ(s.objects.size(), base.objects.size() + 1);
  EXPECT_EQ(s.materials[s.objects.back().material].name, "glass");
}

// objectHeuristics sets K and E on objects that came from the base scene, by name.
TEST(SceneFile, ObjectHeuristicsByName) {
  auto dir = scratchDir("scene_object_heuristics");
  writeText(dir / "s.json",
            R"({"base": "cornell", "objectHeuristics": {"mirrorSphere": {"K": 4, "E": 0.5}}})");
  Scene s = loadSceneFile((dir / "s.json").string());
  int found = 0;
  for (const Object& o : s.objects) {
    bool left = o.name == "mirrorSphere";
    found += left;
    EXPECT_FLOAT_EQ(o.heuristic.K, left ? 4.0f : 1.0f) << o.name;
    EXPECT_FLOAT_EQ(o.heuristic.E, left ? 0.5f : 1.0f) << o.name;
  }
  EXPECT_EQ(found, 1);
}

// Every scene file in scenes/ loads; those made of Tandem's own shapes need no file outside the
// repository, the optional real-model variants load when the third-party scenes are there.
TEST(SceneFile, RepositoryScenesLoad) {
  const bool assets = std::filesystem::exists(test::assetPath("StanfordBunny/bunny.obj"));
  int loaded = 0;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(TANDEM_SOURCE_DIR) + "/scenes")) {
    if (e.path().extension() != ".json") continue;
    std::ifstream in(e.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Third-party files are named through $TANDEM_ASSETS only, never by a path beside the clone.
    EXPECT_EQ(text.find("shared/scenes"), std::string::npos) << e.path();
    if (text.find(kAssetsPrefix) != std::string::npos && !assets) continue;
    Scene s = loadScene(e.path().string());
    EXPECT_GT(s.triangleCount(), 0u) << e.path();
    ++loaded;
  }
  EXPECT_GE(loaded, 16);
}

// A missing third-party file names the scene file, the field and the variable to set.
TEST(SceneFile, MissingThirdPartyAssetSaysHowToFindIt) {
  auto dir = scratchDir("scene_missing_asset");
  writeText(dir / "s.json",
            R"({"base": "cornell", "objects": [{"file": "$TANDEM_ASSETS/NoSuchModel/m.obj"}]})");
  try {
    loadScene((dir / "s.json").string());
    FAIL() << "a missing asset loaded";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("s.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("objects[0].file"), std::string::npos) << msg;
    EXPECT_NE(msg.find("TANDEM_ASSETS"), std::string::npos) << msg;
  }
}

// The heuristic experiment's scenes carry a camera path and objects worth rays.
TEST(SceneFile, ExperimentScenesLoad) {
  for (const char* name :
       {"atrium_spheres", "atrium_statue", "cornell_spheres", "cornell_statue"}) {
    Scene s = loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/" + name + ".json");
    EXPECT_FALSE(s.cameraPath.empty()) << name;
    int relevant = 0;
    for (const Object& o : s.objects) relevant += o.heuristic.K > 1;
    EXPECT_GT(relevant, 0) << name;
  }
}

TEST(BuiltinScenes, AtriumIsAtPaperComplexity) {
  Scene s = makeAtriumScene();
  EXPECT_GT(s.triangleCount(), 200000u);
  EXPECT_LT(s.triangleCount(), 400000u);
  validateScene(s, "atrium");
}

// A binary glTF built by hand: 12-byte header, JSON chunk, BIN chunk with one triangle.
TEST(GltfLoader, BinaryGlb) {
  auto dir = scratchDir("glb");
  std::string json =
      R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36}]})";
  while (json.size() % 4) json += ' ';
  const float verts[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  auto u32 = [](std::string& s, uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); };
  std::string glb;
  u32(glb, 0x46546C67);  // "glTF"
  u32(glb, 2);
  u32(glb, uint32_t(12 + 8 + json.size() + 8 + 36));
  u32(glb, uint32_t(json.size()));
  u32(glb, 0x4E4F534A);  // "JSON"
  glb += json;
  u32(glb, 36);
  u32(glb, 0x004E4942);  // "BIN"
  glb.append(reinterpret_cast<const char*>(verts), 36);
  writeText(dir / "t.glb", glb);
  Scene s = loadScene((dir / "t.glb").string());
  EXPECT_EQ(s.triangleCount(), 1u);
  EXPECT_EQ(s.meshes[0].positions[1].x, 1.0f);
}

// Six constant-colour skybox faces: looking along each axis shows that face's colour.
TEST(SceneFile, SkyboxFaces) {
  auto dir = scratchDir("skybox");
  const Vec3 colours[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
  const char* names[6] = {"px.png", "nx.png", "py.png", "ny.png", "pz.png", "nz.png"};
  for (int k = 0; k < 6; ++k) {
    Buffer img(4, 4, 3);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) img.setRgb(x, y, colours[k]);
    writePng((dir / names[k]).string(), img);
  }
  writeText(dir / "s.json", R"({"objects": [{"shape": "cube", "position": [0, -100, 0]}],
    "skybox": {"faces": ["px.png", "nx.png", "py.png", "ny.png", "pz.png", "nz.png"]}})");
  Scene s = loadSceneFile((dir / "s.json").string());
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int k = 0; k < 6; ++k) {
    Vec3 c = s.skyRadiance(axes[k]);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(c[i], colours[k][i], 1e-5f) << "face " << k;
  }
}

// The knot statue is a closed tube facing outwards: its signed volume (divergence theorem) is the
// tube's pi r^2 L, and each face turns the way its vertex normals point.
TEST(Primitives, TorusKnotIsAClosedOutwardTubeInTheUnitCube) {
  const int segments = 256, sides = 24;
  const float tube = 0.45f, r = tube / (3 + tube);
  Mesh m = makeTorusKnot(2, 3, tube, segments, sides);
  double volume = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* i = &m.indices[3 * t];
    Vec3 a = m.positions[i[0]], b = m.positions[i[1]], c = m.positions[i[2]];
    volume += dot(a, cross(b, c)) / 6.0;
    Vec3 fn = cross(b - a, c - a);
    ASSERT_GT(dot(fn, m.normals[i[0]] + m.normals[i[1]] + m.normals[i[2]]), 0.0f) << t;
  }
  double length = 0;
  Vec3 prev;
  for (int s = 0; s <= segments; ++s) {
    Vec3 centre(0.0f);
    for (int j = 0; j < sides; ++j) centre += m.positions[s * (sides + 1) + j];
    centre = centre / float(sides);
    if (s > 0) length += double(::tandem::length(centre - prev));
    prev = centre;
  }
  EXPECT_NEAR(volume, kPi * r * r * length, 0.02 * kPi * r * r * length);
  for (const Vec3& p : m.positions)
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(p[k]), 1.0f + 1e-5f);
}

// A scene file reached again through `base` or an object's `file` (itself, or along a chain) is an
// input error naming the chain, never a stack overflow; a chain is bounded however it is written.
TEST(SceneFile, ScenesThatReferToThemselvesAreErrorsNamingTheChain) {
  auto dir = scratchDir("scene_cycles");
  auto message = [&](const std::string& file) {
    try {
      loadScene((dir / file).string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  writeText(dir / "self.json", R"({"base": "self.json"})");
  EXPECT_NE(message("self.json").find("refers to itself (self.json -> self.json)"),
            std::string::npos)
      << message("self.json");
  writeText(dir / "a.json", R"({"base": "b.json"})");
  writeText(dir / "b.json", R"({"base": "c.json"})");
  writeText(dir / "c.json", R"({"base": "cornell", "objects": [{"file": "a.json"}]})");
  const std::string chain = message("a.json");
  EXPECT_NE(chain.find("a.json -> b.json -> c.json -> a.json"), std::string::npos) << chain;
  EXPECT_NE(chain.find("objects[0]"), std::string::npos) << chain;  // where c.json names it
  writeText(dir / "obj.json", R"({"base": "cornell", "objects": [{"file": "obj.json"}]})");
  EXPECT_NE(message("obj.json").find("refers to itself"), std::string::npos);
  // A long chain without a cycle: bounded.
  for (int i = 0; i < 40; ++i)
    writeText(dir / ("n" + std::to_string(i) + ".json"),
              R"({"base": "n)" + std::to_string(i + 1) + R"(.json"})");
  writeText(dir / "n40.json", R"({"base": "cornell"})");
  EXPECT_NE(message("n0.json").find("nest deeper than 32"), std::string::npos);
  // The same file twice side by side is no cycle.
  writeText(dir / "twice.json", R"({"base": "cornell", "objects": [{"file": ")" +
                                    writeTetrahedronObj(dir) + R"("}, {"file": ")" +
                                    writeTetrahedronObj(dir) + R"("}]})");
  EXPECT_EQ(message("twice.json"), "loaded");
}
