#include "scene/gltf_preflight.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_io.h"

namespace tandem {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

uint32_t readU32(const unsigned char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);  // GLB is little-endian, as is every machine Tandem runs on
  return v;
}

void putU32(std::vector<unsigned char>& out, uint32_t v) {
  unsigned char b[4];
  std::memcpy(b, &v, 4);
  out.insert(out.end(), b, b + 4);
}

// glTF 1.0 keyed its top-level collections by id (objects); 2.0 lists them (arrays).
bool looksLikeGltf1(const json& j) {
  if (j.contains("asset") && j["asset"].is_object() && j["asset"].contains("version") &&
      j["asset"]["version"].is_string())
    return j["asset"]["version"].get<std::string>().rfind("1", 0) == 0;
  for (const char* k : {"meshes", "accessors", "nodes", "materials", "buffers", "bufferViews"})
    if (j.contains(k) && j[k].is_object()) return true;
  return false;
}

[[noreturn]] void gltf1(const std::string& path) {
  throw InputError(path, "asset.version",
                   "glTF 1.0 is not supported: convert the file to glTF 2.0 (for example with "
                   "gltf-pipeline or Blender)");
}

// Drops "indices" from primitives carrying KHR_draco_mesh_compression: the compressed stream
// holds the triangles; the accessor has no bufferView, which tinygltf refuses. True if any.
bool stripDracoIndices(json& j) {
  bool any = false;
  if (!j.contains("meshes") || !j["meshes"].is_array()) return false;
  for (json& mesh : j["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      continue;
    for (json& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains("KHR_draco_mesh_compression"))
        continue;
      prim.erase("indices");
      any = true;
    }
  }
  return any;
}

// Why `bytes` is not a JSON object, as "line L, column C" of the first offending byte: the JSON
// library's own message would quote the bytes it saw, which need not be printable.
[[noreturn]] void notGltfJson(const std::string& path, const unsigned char* bytes, size_t size) {
  size_t at = size;
  try {
    json j = json::parse(bytes, bytes + size);
    throw InputError(
        path, "",
        std::string("not a glTF JSON file: the top level is ") + j.type_name() + ", not an object");
  } catch (const json::parse_error& e) {
    at = std::min(size, e.byte > 0 ? size_t(e.byte - 1) : size_t(0));
  }
  size_t line = 1, column = 1;
  for (size_t i = 0; i < at; ++i) {
    if (bytes[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  throw InputError(path, "",
                   "not a glTF JSON file (syntax error at line " + std::to_string(line) +
                       ", column " + std::to_string(column) + ")");
}

// The containers tinygltf reads without checking their type: name the field that is wrong.
void checkMeshShapes(const std::string& path, const json& j) {
  if (!j.contains("meshes")) return;
  if (!j["meshes"].is_array())
    throw InputError(path, "meshes",
                     std::string("must be an array of meshes, not ") + j["meshes"].type_name());
  for (size_t m = 0; m < j["meshes"].size(); ++m) {
    const json& mesh = j["meshes"][m];
    const std::string field = "meshes[" + std::to_string(m) + "]";
    if (!mesh.is_object())
      throw InputError(path, field, std::string("must be an object, not ") + mesh.type_name());
    if (mesh.contains("primitives") && !mesh["primitives"].is_array())
      throw InputError(
          path, field + ".primitives",
          std::string("must be an array of primitives, not ") + mesh["primitives"].type_name());
  }
}

}  // namespace

std::string readRegularFile(const std::string& path, std::vector<unsigned char>& out) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return "file not found";
  const uintmax_t size = fs::file_size(path, ec);
  if (ec || size > (uintmax_t(1) << 34)) return "unreadable or larger than 16 GiB";
  out.resize(size_t(size));
  std::ifstream in(path, std::ios::binary);
  if (size > 0 && !in.read(reinterpret_cast<char*>(out.data()), std::streamsize(size)))
    return "cannot read";
  return "";
}

GltfSource preflightGltf(const std::string& path) {
  GltfSource src;
  if (const std::string problem = readRegularFile(path, src.bytes); !problem.empty())
    throw InputError(path, "", problem);
  src.binary = hasExtension(path, ".glb");
  if (src.bytes.empty()) throw InputError(path, "", "empty file");

  // The JSON: the whole file, or a GLB's first chunk.
  size_t jsonStart = 0, jsonLength = src.bytes.size();
  if (src.binary) {
    const unsigned char* b = src.bytes.data();
    if (src.bytes.size() < 12 || std::memcmp(b, "glTF", 4) != 0)
      throw InputError(path, "header", "not a binary glTF (magic 'glTF' missing)");
    if (readU32(b + 4) == 1) gltf1(path);  // KHR_binary_glTF
    if (readU32(b + 4) != 2)
      throw InputError(path, "header", "unknown GLB version " + std::to_string(readU32(b + 4)));
    if (src.bytes.size() < 20 || readU32(b + 16) != 0x4E4F534Au)
      throw InputError(path, "chunk 0", "the first chunk must be JSON");
    jsonStart = 20;
    jsonLength = readU32(b + 12);
    if (jsonLength > src.bytes.size() - 20)
      throw InputError(path, "chunk 0", "JSON chunk length exceeds the file");
    if (readU32(b + 8) > src.bytes.size())
      throw InputError(path, "header", "length exceeds the file");
    // tinygltf 2.7 checks the BIN chunk's length against the file without its 8-byte chunk
    // header, and reads up to 8 bytes past the end (found by fuzz_glb): check it here.
    const size_t binHeader = 20 + jsonLength;
    if (binHeader < src.bytes.size()) {
      if (src.bytes.size() - binHeader < 8)
        throw InputError(path, "chunk 1", "truncated chunk header");
      if (readU32(b + binHeader) > src.bytes.size() - binHeader - 8)
        throw InputError(path, "chunk 1", "BIN chunk length exceeds the file");
    }
  }
  json j = json::parse(src.bytes.begin() + long(jsonStart),
                       src.bytes.begin() + long(jsonStart + jsonLength), nullptr, false);
  if (j.is_discarded() || !j.is_object())
    notGltfJson(path, src.bytes.data() + jsonStart, jsonLength);
  if (looksLikeGltf1(j)) gltf1(path);
  checkMeshShapes(path, j);
  if (!stripDracoIndices(j)) return src;
  src.usesDraco = true;
  const std::string text = j.dump();
  if (!src.binary) {
    src.bytes.assign(text.begin(), text.end());
    return src;
  }
  // Rebuild the GLB around the new JSON chunk (padded with spaces to 4 bytes), binary chunks
  // copied as they were.
  std::vector<unsigned char> glb;
  const size_t padded = (text.size() + 3) & ~size_t(3);
  const size_t rest = src.bytes.size() - (20 + jsonLength);
  if (20 + padded + rest > 0xFFFFFFFFu) throw InputError(path, "header", "GLB over 4 GiB");
  glb.reserve(20 + padded + rest);
  putU32(glb, 0x46546C67u);  // "glTF"
  putU32(glb, 2);
  putU32(glb, uint32_t(12 + 8 + padded + rest));
  putU32(glb, uint32_t(padded));
  putU32(glb, 0x4E4F534Au);
  glb.insert(glb.end(), text.begin(), text.end());
  glb.insert(glb.end(), padded - text.size(), ' ');
  glb.insert(glb.end(), src.bytes.begin() + long(20 + jsonLength), src.bytes.end());
  src.bytes = std::move(glb);
  return src;
}

}  // namespace tandem
