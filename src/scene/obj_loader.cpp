// OBJ + MTL via tinyobjloader. Each (shape, material) pair becomes one object.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <tuple>

#include "core/error.h"
#include "core/image_io.h"
#include "scene/loaders.h"
#include "scene/polygon_triangulation.h"

namespace tandem {
namespace fs = std::filesystem;

namespace {

Vec3 toVec3(const float* v) {
  return {v[0], v[1], v[2]};
}

int loadTexture(Scene& s, std::map<std::string, int>& cache, const std::string& mtlPath,
                const std::string& baseDir, const std::string& name, const std::string& field,
                bool srgb) {
  if (name.empty()) return -1;
  // MTL files written on Windows name textures with backslashes (".\\wood.jpg").
  std::string portable = name;
  std::replace(portable.begin(), portable.end(), '\\', '/');
  std::string path = (fs::path(baseDir) / portable).string();
  auto key = path + (srgb ? "#srgb" : "#linear");
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  if (!fs::exists(path)) throw InputError(mtlPath, field, "texture '" + name + "' not found");
  int id = s.addTexture(textureFromImage(path, loadTextureFile(path), srgb));
  cache[key] = id;
  return id;
}

Material convertMaterial(const tinyobj::material_t& m, Scene& s, std::map<std::string, int>& cache,
                         const std::string& mtlPath, const std::string& baseDir) {
  Material out;
  out.name = m.name;
  out.doubleSided = true;  // OBJ has no notion of one-sided faces
  out.ambient = toVec3(m.ambient);
  out.diffuse = toVec3(m.diffuse);
  out.specular = toVec3(m.specular);
  out.emission = toVec3(m.emission);
  out.specularExponent = std::clamp(m.shininess, 1.0f, 4096.0f);
  out.ior = m.ior > 0 ? m.ior : 1.0f;
  out.opacity = std::clamp(m.dissolve, 0.0f, 1.0f);  // tinyobjloader maps Tr to 1 - Tr
  out.diffuseOpacity = out.opacity;
  switch (m.illum) {
    case 3:  // reflection on, ray traced
    case 5:  // Fresnel mirror
      out.reflectivity = m.illum == 5 ? 1.0f : std::clamp(maxComponent(out.specular), 0.0f, 1.0f);
      break;
    case 4:  // glass, ray-traced reflection
    case 9:  // glass, no ray-traced reflection
      out.opacity = std::min(out.opacity, 0.1f);
      out.reflectivity = m.illum == 4 ? std::clamp(maxComponent(out.specular), 0.0f, 1.0f) : 0.0f;
      break;
    case 6:  // refraction and ray-traced reflection
      out.opacity = 0.0f;
      out.reflectivity = std::clamp(maxComponent(out.specular), 0.0f, 1.0f);
      break;
    case 7: {  // refraction, reflection weighted by Fresnel: Schlick's F0 of the IOR, times Ks
      out.opacity = 0.0f;
      const float f0 = (out.ior - 1.0f) / (out.ior + 1.0f);
      out.reflectivity = std::clamp(maxComponent(out.specular) * f0 * f0, 0.0f, 1.0f);
      break;
    }
    default:
      break;
  }
  // Tf filters what a transmissive material lets through; tinyobjloader leaves 0 when absent.
  const Vec3 tf = toVec3(m.transmittance);
  if (maxComponent(tf) > 0.0f) out.transmissionFilter = vmin(vmax(tf, Vec3(0.0f)), Vec3(1.0f));
  for (float* c : {&out.diffuse.x, &out.diffuse.y, &out.diffuse.z, &out.specular.x, &out.specular.y,
                   &out.specular.z})
    *c = std::clamp(*c, 0.0f, 1.0f);
  out.emission = vmax(out.emission, Vec3(0.0f));
  if (!isFinite(out.emission) || !isFinite(out.diffuse) || !std::isfinite(out.ior))
    throw InputError(mtlPath, "material '" + m.name + "'", "non-finite value");
  out.diffuseTexture = loadTexture(s, cache, mtlPath, baseDir, m.diffuse_texname, "map_Kd", true);
  out.emissionTexture = loadTexture(s, cache, mtlPath, baseDir, m.emissive_texname, "map_Ke", true);
  out.specularTexture = loadTexture(s, cache, mtlPath, baseDir, m.specular_texname, "map_Ks", true);
  out.normalTexture = loadTexture(s, cache, mtlPath, baseDir, m.normal_texname, "norm", false);
  if (out.diffuseTexture >= 0 && m.diffuse_texopt.scale[0] != 1.0f) {
    out.tiling = {m.diffuse_texopt.scale[0], m.diffuse_texopt.scale[1]};
  }
  if (out.diffuseTexture >= 0)
    out.offset = {m.diffuse_texopt.origin_offset[0], m.diffuse_texopt.origin_offset[1]};
  return out;
}

// tinyobjloader reads 'nan'/'inf' coordinates leniently (as 0 or a huge value); check every
// vertex line ourselves so such files fail with the line that is wrong.
void checkVertexLines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (size_t n = 1; std::getline(in, line); ++n) {
    if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
    std::istringstream ss(line.substr(2));
    std::string tok;
    for (int k = 0; k < 3 && ss >> tok; ++k) {
      char* end = nullptr;
      double d = std::strtod(tok.c_str(), &end);
      if (end == tok.c_str() || !std::isfinite(d))
        throw InputError(path, "line " + std::to_string(n),
                         "vertex coordinate '" + tok + "' is NaN or infinite or not a number");
    }
  }
}

// Faces of more than kHugeFace vertices: tinyobjloader stores a face's vertex count in a byte and
// triangulates in quadratic time (a 100k-vertex face took minutes). When a file has such faces,
// its text is handed to tinyobjloader with each of them replaced by our triangles
// (scene/polygon_triangulation.h, bounded time), and its MTL libraries' text beside it; so is a
// file whose text had to be decoded (decodeText). Returns false (nothing to do) for the usual
// file.
constexpr size_t kHugeFace = 200;

// The file's text as UTF-8 without a byte-order mark: a UTF-8 BOM is dropped, UTF-16 (either
// byte order, by its BOM) is narrowed when it holds only ASCII and refused otherwise. Returns
// false when the file needed nothing of that.
bool decodeText(const std::string& path, std::string& text) {
  std::ifstream in(path, std::ios::binary);
  std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto at = [&](size_t i) { return static_cast<unsigned char>(raw[i]); };
  if (raw.size() >= 3 && at(0) == 0xEF && at(1) == 0xBB && at(2) == 0xBF) {
    text = raw.substr(3);
    return true;
  }
  if (raw.size() >= 2 && ((at(0) == 0xFF && at(1) == 0xFE) || (at(0) == 0xFE && at(1) == 0xFF))) {
    const bool little = at(0) == 0xFF;
    text.clear();
    for (size_t i = 2; i + 1 < raw.size(); i += 2) {
      const unsigned lo = little ? at(i) : at(i + 1), hi = little ? at(i + 1) : at(i);
      if (hi != 0 || lo >= 0x80)
        throw InputError(path, "", "UTF-16 text with characters beyond ASCII: save it as UTF-8");
      text += char(lo);
    }
    return true;
  }
  return false;
}

bool rewriteHugeFaces(const std::string& path, std::string& obj, std::string& mtl) {
  std::string decoded;
  const bool recoded = decodeText(path, decoded);
  std::ifstream file;
  std::istringstream memory;
  if (recoded)
    memory.str(decoded);
  else
    file.open(path, std::ios::binary);
  std::istream& in = recoded ? static_cast<std::istream&>(memory) : file;
  std::string line;
  std::vector<Vec3> positions;
  std::ostringstream out;
  std::vector<std::string> libs;
  bool huge = false;
  for (size_t n = 1; std::getline(in, line); ++n) {
    if (line.size() > 1 && line[0] == 'v' && (line[1] == ' ' || line[1] == '\t')) {
      std::istringstream ss(line.substr(2));
      Vec3 v{0.0f};
      ss >> v.x >> v.y >> v.z;
      positions.push_back(v);
    } else if (line.rfind("mtllib", 0) == 0) {
      std::istringstream ss(line.substr(6));
      std::string name;
      while (ss >> name) libs.push_back(name);
    } else if (line.size() > 1 && line[0] == 'f' && (line[1] == ' ' || line[1] == '\t')) {
      std::istringstream ss(line.substr(2));
      std::vector<std::string> tokens;
      std::string tok;
      while (ss >> tok) tokens.push_back(tok);
      if (tokens.size() > kHugeFace) {
        huge = true;
        std::vector<Vec3> polygon;
        for (const std::string& t : tokens) {
          long i = std::strtol(t.c_str(), nullptr, 10);
          if (i < 0) i += long(positions.size()) + 1;  // relative to the vertices so far
          if (i < 1 || size_t(i) > positions.size())
            throw InputError(path, "line " + std::to_string(n), "vertex index out of range");
          polygon.push_back(positions[size_t(i - 1)]);
        }
        for (const auto& t : triangulatePolygon(polygon))
          out << "f " << tokens[t[0]] << ' ' << tokens[t[1]] << ' ' << tokens[t[2]] << '\n';
        continue;
      }
    }
    out << line << '\n';
  }
  if (!huge && !recoded) return false;
  obj = out.str();
  for (const std::string& lib : libs) {
    // Regular files only: reading a folder named by `mtllib` throws from inside libstdc++
    // (found by fuzz_obj). A missing library is left out, as tinyobjloader does.
    const fs::path mp = fs::path(path).parent_path() / lib;
    std::error_code ec;
    if (!fs::is_regular_file(mp, ec)) continue;
    std::ifstream m(mp, std::ios::binary);
    try {
      mtl +=
          std::string(std::istreambuf_iterator<char>(m), std::istreambuf_iterator<char>()) + '\n';
    } catch (const std::exception& e) {
      throw InputError(mp.string(), "", std::string("cannot read: ") + e.what());
    }
  }
  return true;
}

}  // namespace

// A binary file (an FBX, a .blend, a zip) renamed .obj parses as an OBJ with no triangles; say
// what it is instead. OBJ is text: a NUL byte in the first 64 KiB (outside UTF-16, which the
// loader converts) is proof enough.
static void checkObjIsText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(65536, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  const std::pair<const char*, const char*> magics[] = {{"Kaydara FBX Binary", "a binary FBX file"},
                                                        {"BLENDER", "a Blender .blend file"},
                                                        {"glTF", "a binary glTF (GLB) file"},
                                                        {"PK\x03\x04", "a zip archive"},
                                                        {"\x89PNG", "a PNG image"}};
  for (const auto& [magic, what] : magics)
    if (head.rfind(magic, 0) == 0)
      throw InputError(path, "", std::string("not an OBJ text file (it is ") + what + ")");
  const bool utf16 = head.rfind("\xff\xfe", 0) == 0 || head.rfind("\xfe\xff", 0) == 0;
  if (!utf16 && head.find('\0') != std::string::npos)
    throw InputError(path, "", "not an OBJ text file (binary data)");
}

Scene loadObj(const std::string& path) {
  if (!fs::is_regular_file(path)) throw InputError(path, "", "file not found");
  checkObjIsText(path);
  checkVertexLines(path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = fs::path(path).parent_path().string();
  tinyobj::ObjReader reader;
  std::string objText, mtlText;
  const bool rewritten = rewriteHugeFaces(path, objText, mtlText);
  if (!(rewritten ? reader.ParseFromString(objText, mtlText, config)
                  : reader.ParseFromFile(path, config))) {
    std::string err = reader.Error();
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    throw InputError(path, "", "cannot parse OBJ: " + (err.empty() ? "unknown error" : err));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  Scene s;
  s.name = fs::path(path).stem().string();
  s.stats.sources.push_back(path);
  std::map<std::string, int> texCache;
  std::string baseDir = config.mtl_search_path;
  for (const auto& m : reader.GetMaterials())
    s.addMaterial(convertMaterial(m, s, texCache, path + " (mtl)", baseDir));
  int defaultMat = -1;
  const size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3,
               nt = attrib.texcoords.size() / 2;
  for (size_t v = 0; v < nv; ++v)
    if (!isFinite(toVec3(&attrib.vertices[3 * v])))
      throw InputError(path, "v " + std::to_string(v + 1), "vertex position is NaN or infinite");

  for (const auto& shape : reader.GetShapes()) {
    const auto& mesh = shape.mesh;
    // Group faces by material so that every object has exactly one material.
    std::map<int, Mesh> byMaterial;
    std::map<int, std::map<std::tuple<int, int, int>, uint32_t>> vertexIds;
    std::map<int, bool> hasNormals;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      if (mesh.num_face_vertices[f] != 3) continue;  // lines/points after triangulation
      int mat = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      if (mat >= int(s.materials.size())) mat = -1;
      Mesh& m = byMaterial[mat];
      auto& ids = vertexIds[mat];
      if (!hasNormals.count(mat)) hasNormals[mat] = true;
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t& idx = mesh.indices[3 * f + k];
        if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv)
          throw InputError(path, "shape '" + shape.name + "' face " + std::to_string(f + 1),
                           "vertex index out of range");
        if (idx.normal_index >= 0 && size_t(idx.normal_index) >= nn)
          throw InputError(path, "shape '" + shape.name + "' face " + std::to_string(f + 1),
                           "normal index out of range");
        if (idx.texcoord_index >= 0 && size_t(idx.texcoord_index) >= nt)
          throw InputError(path, "shape '" + shape.name + "' face " + std::to_string(f + 1),
                           "texcoord index out of range");
        if (idx.normal_index < 0) hasNormals[mat] = false;
        auto key = std::make_tuple(idx.vertex_index, idx.normal_index, idx.texcoord_index);
        auto it = ids.find(key);
        if (it == ids.end()) {
          uint32_t id = uint32_t(m.positions.size());
          m.positions.push_back(toVec3(&attrib.vertices[3 * idx.vertex_index]));
          m.normals.push_back(idx.normal_index >= 0 ? toVec3(&attrib.normals[3 * idx.normal_index])
                                                    : Vec3(0.0f));
          m.uvs.push_back(idx.texcoord_index >= 0
                              ? Vec2(attrib.texcoords[2 * idx.texcoord_index],
                                     1.0f - attrib.texcoords[2 * idx.texcoord_index + 1])
                              : Vec2(0, 0));
          it = ids.emplace(key, id).first;
        }
        m.indices.push_back(it->second);
      }
    }
    for (auto& [mat, m] : byMaterial) {
      s.stats.degenerateTriangles += removeDegenerateTriangles(m);
      if (m.indices.empty()) continue;
      if (!hasNormals[mat]) m.normals.clear();
      for (const Vec3& n : m.normals)
        if (!isFinite(n))
          throw InputError(path, "shape '" + shape.name + "'", "normal is NaN or infinite");
      int material = mat;
      if (material < 0) {
        if (defaultMat < 0) {
          Material plain;
          plain.doubleSided = true;  // as every OBJ material
          defaultMat = s.addMaterial(plain);
        }
        material = defaultMat;
      }
      std::string name = shape.name.empty() ? "shape" : shape.name;
      if (byMaterial.size() > 1) name += "/" + s.materials[material].name;
      s.addObject(name, s.addMesh(std::move(m)), material);
    }
  }
  if (s.objects.empty()) throw InputError(path, "", "no triangles");
  validateScene(s, path);
  return s;
}

}  // namespace tandem
