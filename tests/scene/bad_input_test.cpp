// Every bad input gets an InputError naming the file, the field and the problem.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "pipeline/render_limits.h"
#include "scene/builtin_scenes.h"
#include "scene/loaders.h"
#include "test_util.h"

using namespace tandem;
using tandem::test::scratchDir;
using tandem::test::writeText;

namespace {

// Loads `text` saved as `name` and expects an InputError whose message holds every fragment.
void expectLoadError(const std::string& name, const std::string& text,
                     std::vector<std::string> fragments) {
  auto dir = scratchDir("bad_" + name);
  auto path = (dir / name).string();
  writeText(dir / name, text);
  try {
    loadSceneByExtension(path);
    FAIL() << "no error for " << name;
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    for (const auto& f : fragments)
      EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
  }
}

const std::string kTriangleGltfHead =
    R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],)";
const std::string kBuffer =
    R"("buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}])";

}  // namespace

TEST(BadInput, MissingFiles) {
  EXPECT_THROW(loadSceneByExtension("/nonexistent/x.obj"), InputError);
  EXPECT_THROW(loadSceneByExtension("/nonexistent/x.gltf"), InputError);
  EXPECT_THROW(loadSceneByExtension("/nonexistent/x.json"), InputError);
  EXPECT_THROW(loadScene("no-such-builtin"), InputError);
  EXPECT_THROW(loadSceneByExtension("/tmp/scene.xyz"), InputError);
}

TEST(BadInput, MalformedJson) {
  expectLoadError("a.json", "{\"objects\": [", {"malformed JSON"});
}

TEST(BadInput, UnknownJsonField) {
  expectLoadError("b.json", R"({"objects": [{"shape": "cube", "positon": [0, 0, 0]}]})",
                  {"objects[0].positon", "unknown field"});
}

TEST(BadInput, GazeTraceFields) {
  expectLoadError(
      "g1.json",
      R"({"objects": [{"shape": "cube"}], "gazeTrace": [{"time": 0, "gaze": [1.5, 0.5]}]})",
      {"gazeTrace[0].gaze", "[0, 1]"});
  expectLoadError("g2.json",
                  R"({"objects": [{"shape": "cube"}], "gazeTrace": [{"time": 1}, {"time": 0}]})",
                  {"gazeTrace[1].time", "sorted"});
  expectLoadError("g3.json", R"({"objects": [{"shape": "cube"}], "gazeTrace": []})", {"gazeTrace"});
  expectLoadError("g4.json", R"({"objects": [{"shape": "cube"}], "baseLights": 3})",
                  {"baseLights"});
}

TEST(BadInput, StereoFields) {
  expectLoadError("st1.json", R"({"objects": [{"shape": "cube"}], "stereo": {"ipd": -0.1}})",
                  {"stereo.ipd"});
  expectLoadError("st2.json", R"({"objects": [{"shape": "cube"}], "stereo": {"ipb": 0.1}})",
                  {"stereo.ipb", "unknown field"});
  expectLoadError("st3.json", R"({"objects": [{"shape": "cube"}], "stereo": {"converged": 1}})",
                  {"stereo.converged"});
  // A good one loads with its values.
  auto dir = scratchDir("good_stereo");
  writeText(
      dir / "s.json",
      R"({"objects": [{"shape": "cube"}], "stereo": {"ipd": 0.07, "converged": true, "convergence": 3}})");
  const Scene s = loadSceneByExtension((dir / "s.json").string());
  EXPECT_TRUE(s.stereo.enabled);
  EXPECT_FLOAT_EQ(s.stereo.ipd, 0.07f);
  EXPECT_TRUE(s.stereo.converged);
  EXPECT_FLOAT_EQ(s.stereo.convergence, 3.0f);
}

TEST(BadInput, WrongJsonType) {
  expectLoadError("c.json", R"({"objects": [{"shape": "cube", "position": "up"}]})",
                  {"objects[0].position", "array of 3"});
  expectLoadError("d.json", R"({"objects": [{"shape": "sphere", "slices": 2.5}]})",
                  {"slices", "integer"});
  expectLoadError("e.json", R"({"materials": {"m": {"ior": -1}}, "objects": [{"shape": "cube"}]})",
                  {"materials.m.ior", "out of range"});
  // Finite as a double, infinite as the float it is stored in.
  expectLoadError(
      "f.json",
      R"({"materials": {"m": {"emission": [1e39, 0, 0]}}, "objects": [{"shape": "cube"}]})",
      {"materials.m.emission", "within +-3.4e38"});
}

// The brightest emission a float holds, on a large mesh, makes a light of finite intensity.
TEST(BadInput, EmissiveLightIntensityStaysFinite) {
  auto dir = scratchDir("bright_emitter");
  writeText(dir / "s.json",
            R"({"materials": {"m": {"emission": [3e38, 3e38, 3e38]}},
                "objects": [{"shape": "sphere", "material": "m", "scale": [10, 10, 10]}]})");
  Scene s = loadScene((dir / "s.json").string());
  ASSERT_EQ(s.lights.size(), 1u);  // auto: the scene has no punctual lights
  EXPECT_TRUE(std::isfinite(s.lights[0].intensity));
  EXPECT_GT(s.lights[0].intensity, 1e38f);
}

TEST(BadInput, UnknownMaterialAndShape) {
  expectLoadError("f.json", R"({"objects": [{"shape": "cube", "material": "nope"}]})",
                  {"objects[0].material", "unknown material 'nope'"});
  expectLoadError("g.json", R"({"objects": [{"shape": "torus"}]})", {"objects[0].shape", "torus"});
}

TEST(BadInput, MissingTexture) {
  expectLoadError(
      "h.json",
      R"({"materials": {"m": {"diffuseMap": "missing.png"}}, "objects": [{"shape": "cube"}]})",
      {"materials.m.diffuseMap", "missing.png", "not found"});
}

TEST(BadInput, ObjIndexOutOfRange) {
  expectLoadError("i.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", {});
}

TEST(BadInput, ObjNanVertex) {
  expectLoadError("j.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", {"NaN"});
}

TEST(BadInput, ObjInfVertex) {
  expectLoadError("k.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n", {"NaN or infinite"});
}

TEST(BadInput, ObjMissingTexture) {
  auto dir = scratchDir("obj_tex");
  writeText(dir / "m.mtl", "newmtl a\nKd 1 1 1\nmap_Kd nothere.png\n");
  writeText(dir / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  try {
    loadObj((dir / "m.obj").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("map_Kd"), std::string::npos) << e.what();
  }
}

TEST(BadInput, DegenerateTrianglesAreSkippedAndCounted) {
  auto dir = scratchDir("degenerate");
  writeText(dir / "d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 3\n");
  Scene s = loadObj((dir / "d.obj").string());
  EXPECT_EQ(s.triangleCount(), 1u);
  EXPECT_EQ(s.stats.degenerateTriangles, 2u);
}

TEST(BadInput, GltfRequiredExtensionUnsupported) {
  expectLoadError(
      "l.gltf",
      R"({"asset": {"version": "2.0"}, "extensionsRequired": ["EXT_meshopt_compression"],
                                 "extensionsUsed": ["EXT_meshopt_compression"]})",
      {"extensionsRequired", "EXT_meshopt_compression"});
}

TEST(BadInput, GltfAccessorOutOfRange) {
  expectLoadError("m.gltf",
                  kTriangleGltfHead +
                      R"("meshes": [{"primitives": [{"attributes": {"POSITION": 5}}]}],
      "accessors": [], "bufferViews": [], )" +
                      kBuffer + "}",
                  {"POSITION", "out of range"});
}

TEST(BadInput, GltfIndexOutOfRange) {
  // Indices 0, 1, 9 as unsigned bytes after the 36 position bytes.
  expectLoadError(
      "n.gltf",
      kTriangleGltfHead +
          R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                    {"bufferView": 1, "componentType": 5121, "count": 3, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 1, "byteLength": 3}],
      "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"},
                  {"byteLength": 3, "uri": "data:application/octet-stream;base64,AAEJ"}]})",
      {"indices", "index 9 out of range"});
}

TEST(BadInput, GltfNanVertex) {
  // Second vertex x = NaN (0x7fc00000).
  expectLoadError(
      "o.gltf",
      kTriangleGltfHead + R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAADAfwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})",
      {"POSITION", "NaN"});
}

TEST(BadInput, GltfMalformed) {
  expectLoadError("p.gltf", "{ not json", {"not a glTF JSON file", "line 1, column 4"});
}

TEST(BadInput, GltfMissingImage) {
  expectLoadError(
      "q.gltf",
      kTriangleGltfHead +
          R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
      "textures": [{"source": 0}], "images": [{"uri": "nothere.png"}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}], )" +
          kBuffer + "}",
      {"materials[0].baseColorTexture", "nothere.png"});
}

TEST(BadInput, GltfAbsurdAccessorCount) {
  expectLoadError("r.gltf",
                  kTriangleGltfHead +
                      R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4611686018427387904, "type": "VEC3"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}], )" +
                      kBuffer + "}",
                  {"POSITION", "count exceeds its buffer"});
  expectLoadError("s.gltf",
                  kTriangleGltfHead +
                      R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"componentType": 5126, "count": 4611686018427387904, "type": "VEC3"}], )" +
                      kBuffer + "}",
                  {"POSITION", "absurd count"});
}

TEST(BadInput, ObjectHeuristics) {
  expectLoadError("oh1.json", R"({"base": "cornell", "objectHeuristics": {"nosuch": {"K": 2}}})",
                  {"objectHeuristics.nosuch", "no object of that name"});
  expectLoadError("oh2.json", R"({"base": "cornell", "objectHeuristics": {"floor": {"K": -1}}})",
                  {"objectHeuristics.floor", "K"});
  expectLoadError("oh3.json", R"({"base": "cornell", "objectHeuristics": [1]})",
                  {"objectHeuristics", "expected an object"});
}

// Bad lens values (Tan et al. 2022's thin lens) name the field.
TEST(BadInput, LensFields) {
  expectLoadError("l1.json", R"({"objects": [{"shape": "cube"}], "camera": {"aperture": -0.1}})",
                  {"camera.aperture"});
  expectLoadError("l2.json", R"({"objects": [{"shape": "cube"}], "camera": {"focusDistance": 0}})",
                  {"camera.focusDistance"});
  expectLoadError("l3.json", R"({"objects": [{"shape": "cube"}], "camera": {"focusDistance": -2}})",
                  {"camera.focusDistance"});
  for (int blades : {1, 2})
    expectLoadError("l4.json",
                    R"({"objects": [{"shape": "cube"}], "camera": {"apertureBlades": )" +
                        std::to_string(blades) + "}}",
                    {"camera.apertureBlades", "at least 3"});
}

// A buffer URI naming a directory (here the file's own folder) made tinygltf's reader allocate
// 2^63 bytes (found by fuzz_gltf): only regular files are read.
TEST(BadInput, GltfBufferUriNamingAFolder) {
  for (const char* uri : {"", ".", "%2E"})
    expectLoadError("dir.gltf",
                    kTriangleGltfHead +
                        R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "buffers": [{"byteLength": 36, "uri": ")" +
                        std::string(uri) + R"("}]})",
                    {"cannot parse glTF"});
}

// Files that are not what their extension says are named for what they are, and a message never
// carries the file's raw bytes (control characters) to the terminal.
TEST(BadInput, BinaryFileNamedObjIsNotAnObjTextFile) {
  expectLoadError("model.obj", std::string("Kaydara FBX Binary  \0\x1a\0", 23) + "\x01\x02geometry",
                  {"not an OBJ text file", "binary FBX"});
  expectLoadError("blob.obj", std::string("v 0 0 0\n\0\0\x7f\x03", 12), {"not an OBJ text file"});
}

TEST(BadInput, GltfThatIsNotJsonSaysWhereAndStaysPrintable) {
  auto dir = scratchDir("bad_gltf_bytes");
  writeText(dir / "x.gltf",
            std::string("{\"asset\": {\"version\": \"2.0\"},\n  \x01\x1b[31m\xff", 35));
  try {
    loadSceneByExtension((dir / "x.gltf").string());
    FAIL() << "bytes loaded as glTF";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("not a glTF JSON file"), std::string::npos) << msg;
    EXPECT_NE(msg.find("line 2, column 3"), std::string::npos) << msg;
    for (unsigned char c : msg) EXPECT_TRUE(c >= 0x20 && c != 0x7f) << int(c) << " in " << msg;
  }
  expectLoadError("array.gltf", "[1, 2]", {"not a glTF JSON file", "array"});
}

TEST(BadInput, GltfPrimitivesAsAnObjectNamesTheField) {
  expectLoadError(
      "prim.gltf",
      kTriangleGltfHead + R"("meshes": [{"primitives": {"attributes": {"POSITION": 0}}}]})",
      {"meshes[0].primitives", "must be an array", "object"});
}

// A scene too large to render on the machine is an input error naming the scene and what it
// needs, part by part; a thousand shadow-casting lights count the shadow maps' budget once.
TEST(BadInput, SceneThatCannotFitNamesWhatItNeeds) {
  Scene s = makeBuiltinScene("cornell");
  Light l;
  s.lights.assign(1000, l);
  const MemoryNeed n = memoryNeed(s, 1280, 720, false);
  EXPECT_NEAR(n.buffers, 1280.0 * 720.0 * 175.0, 1.0);
  EXPECT_GT(n.geometry, double(s.memoryBytes()));
  EXPECT_GT(n.shadowMaps, 0.0);
  EXPECT_LT(n.shadowMaps, 1.5 * 1073741824.0);  // the texel budget, not 1000 lights' maps
  EXPECT_NO_THROW(checkSceneFits("s.json", "memory", s, 1280, 720, false, 16.0 * 1073741824.0));
  try {
    checkSceneFits("s.json", "memory", s, 1280, 720, false, 0.5 * 1073741824.0);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("s.json"), std::string::npos) << m;
    EXPECT_NE(m.find("memory"), std::string::npos) << m;
    EXPECT_NE(m.find("needs about"), std::string::npos) << m;
    EXPECT_NE(m.find("shadow maps"), std::string::npos) << m;
    EXPECT_NE(m.find("this machine has 0.5 GiB"), std::string::npos) << m;
  }
  for (Light& x : s.lights) x.castsShadows = false;
  EXPECT_EQ(memoryNeed(s, 64, 64, false).shadowMaps, 0.0);
}
