// glTF 2.0 (.gltf/.glb) via tinygltf. Each mesh primitive placed by a node becomes one object.
// Material mapping (metallic-roughness -> Tandem) is documented in docs/scene-format.md.
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <set>

#include "core/error.h"
#include "core/image_io.h"
#include "scene/gltf_draco.h"
#include "scene/gltf_preflight.h"
#include "scene/loaders.h"

namespace tandem {
namespace fs = std::filesystem;

namespace {

const std::set<std::string> kSupportedExtensions = {
    "KHR_texture_transform",           "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_materials_emissive_strength", "KHR_lights_punctual",        "KHR_draco_mesh_compression"};

struct Ctx {
  const std::string& path;
  const tinygltf::Model& model;
  Scene& scene;
  std::map<std::pair<int, bool>, int> textureIds;  // (gltf texture, srgb) -> scene texture
};

// One component at `p` as a float (normalised integers mapped to [0,1] / [-1,1]).
float decodeComponent(const unsigned char* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? *p / 255.0f : *p;
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t b;
      std::memcpy(&b, p, 1);
      return normalized ? std::max(b / 127.0f, -1.0f) : b;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t u;
      std::memcpy(&u, p, 2);
      return normalized ? u / 65535.0f : u;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t u;
      std::memcpy(&u, p, 2);
      return normalized ? std::max(u / 32767.0f, -1.0f) : u;
    }
    default:
      return std::nanf("");  // the caller refuses the componentType before reading
  }
}

bool isVertexComponentType(int t) {
  return t == TINYGLTF_COMPONENT_TYPE_FLOAT || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         t == TINYGLTF_COMPONENT_TYPE_SHORT;
}

// The bytes of `count` elements of `elementSize` bytes, `stride` apart (0: packed), starting
// `byteOffset` into buffer view `view`: every bound checked against the view and its buffer.
const unsigned char* viewBytes(const Ctx& c, int view, size_t byteOffset, size_t count,
                               size_t elementSize, size_t* stride, const std::string& field) {
  const auto& m = c.model;
  if (view < 0 || view >= int(m.bufferViews.size()))
    throw InputError(c.path, field, "bufferView index out of range");
  const tinygltf::BufferView& bv = m.bufferViews[size_t(view)];
  if (bv.buffer < 0 || bv.buffer >= int(m.buffers.size()))
    throw InputError(c.path, field, "buffer index out of range");
  const auto& buf = m.buffers[size_t(bv.buffer)].data;
  if (*stride == 0) *stride = elementSize;
  if (*stride < elementSize) throw InputError(c.path, field, "byteStride below the element size");
  // Each element takes at least one byte: a larger count is bogus (and could overflow below).
  if (count > buf.size()) throw InputError(c.path, field, "count exceeds its buffer");
  const size_t start = bv.byteOffset + byteOffset;
  if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset)
    throw InputError(c.path, field, "bufferView extends past its buffer");
  if (count > 0) {
    const size_t end = start + *stride * (count - 1) + elementSize;
    if (end > bv.byteOffset + bv.byteLength)
      throw InputError(c.path, field, "data extends past its buffer view");
  }
  return buf.data() + start;
}

// Reads an accessor as floats, `wantComponents` per element, sparse substitutions applied.
std::vector<float> readAccessor(const Ctx& c, int index, int wantComponents,
                                const std::string& what) {
  const auto& m = c.model;
  if (index < 0 || index >= int(m.accessors.size()))
    throw InputError(c.path, what, "accessor index " + std::to_string(index) + " out of range");
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  const std::string field = what + " (accessor " + std::to_string(index) + ")";
  const int comps = tinygltf::GetNumComponentsInType(uint32_t(a.type));
  if (comps != wantComponents)
    throw InputError(c.path, field, "expected " + std::to_string(wantComponents) + " components");
  if (!isVertexComponentType(a.componentType))
    throw InputError(c.path, field, "unsupported componentType for vertex data");
  const size_t csize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType)));
  const size_t esize = csize * size_t(comps);
  // Without a buffer view the data is all zeros (sparse accessors fill some in); cap the count
  // so a bogus one cannot make us allocate without limit.
  if (a.bufferView < 0 && a.count > (size_t(1) << 26))
    throw InputError(c.path, field, "absurd count without a bufferView");
  std::vector<float> out;
  if (a.bufferView >= 0) {
    size_t stride = a.bufferView < int(m.bufferViews.size())
                        ? m.bufferViews[size_t(a.bufferView)].byteStride
                        : 0;
    const unsigned char* base =
        viewBytes(c, a.bufferView, a.byteOffset, a.count, esize, &stride, field);
    out.resize(a.count * size_t(comps));
    for (size_t i = 0; i < a.count; ++i)
      for (int k = 0; k < comps; ++k)
        out[i * size_t(comps) + size_t(k)] =
            decodeComponent(base + i * stride + size_t(k) * csize, a.componentType, a.normalized);
  } else {
    out.assign(a.count * size_t(comps), 0.0f);
  }
  if (a.sparse.isSparse) {
    // Sparse: `count` element indices (strictly increasing) and their packed values.
    const auto& sp = a.sparse;
    const std::string sf = field + ".sparse";
    if (sp.count < 1 || size_t(sp.count) > a.count)
      throw InputError(c.path, sf + ".count", "must be in [1, accessor count]");
    const int it = sp.indices.componentType;
    if (it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      throw InputError(c.path, sf + ".indices.componentType", "must be an unsigned integer type");
    if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0)
      throw InputError(c.path, sf, "negative byteOffset");
    const size_t isize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(it)));
    size_t istride = 0, vstride = 0;  // sparse data is tightly packed
    const unsigned char* ip = viewBytes(c, sp.indices.bufferView, size_t(sp.indices.byteOffset),
                                        size_t(sp.count), isize, &istride, sf + ".indices");
    const unsigned char* vp = viewBytes(c, sp.values.bufferView, size_t(sp.values.byteOffset),
                                        size_t(sp.count), esize, &vstride, sf + ".values");
    for (size_t i = 0; i < size_t(sp.count); ++i) {
      uint32_t e = 0;
      if (isize == 1) {
        e = ip[i];
      } else if (isize == 2) {
        uint16_t u;
        std::memcpy(&u, ip + 2 * i, 2);
        e = u;
      } else {
        std::memcpy(&e, ip + 4 * i, 4);
      }
      if (e >= a.count)
        throw InputError(c.path, sf + ".indices", "index " + std::to_string(e) + " out of range");
      for (int k = 0; k < comps; ++k)
        out[size_t(e) * size_t(comps) + size_t(k)] =
            decodeComponent(vp + i * esize + size_t(k) * csize, a.componentType, a.normalized);
    }
  }
  for (float v : out)
    if (!std::isfinite(v)) throw InputError(c.path, field, "value is NaN or infinite");
  return out;
}

std::vector<uint32_t> readIndices(const Ctx& c, int index, size_t vertexCount) {
  const auto& m = c.model;
  const std::string field = "indices (accessor " + std::to_string(index) + ")";
  if (index < 0 || index >= int(m.accessors.size()))
    throw InputError(c.path, field, "accessor index out of range");
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  if (a.type != TINYGLTF_TYPE_SCALAR || a.bufferView < 0 || a.sparse.isSparse)
    throw InputError(c.path, field, "indices must be a scalar accessor with a bufferView");
  const int t = a.componentType;
  if (t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw InputError(c.path, field, "invalid componentType");
  const size_t csize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(t)));
  size_t stride =
      a.bufferView < int(m.bufferViews.size()) ? m.bufferViews[size_t(a.bufferView)].byteStride : 0;
  const unsigned char* base =
      viewBytes(c, a.bufferView, a.byteOffset, a.count, csize, &stride, field);
  std::vector<uint32_t> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = base + i * stride;
    uint32_t v = 0;
    if (csize == 1) {
      v = *p;
    } else if (csize == 2) {
      uint16_t u;
      std::memcpy(&u, p, 2);
      v = u;
    } else {
      std::memcpy(&v, p, 4);
    }
    if (v >= vertexCount)
      throw InputError(c.path, field,
                       "index " + std::to_string(v) + " out of range (" +
                           std::to_string(vertexCount) + " vertices)");
    out[i] = v;
  }
  return out;
}

// Triangle list from a primitive's vertex sequence by glTF topology (spec 3.7.2.1): strips
// alternate winding so every triangle faces the same way; fans pivot on the first vertex.
std::vector<uint32_t> trianglesFromTopology(const std::vector<uint32_t>& v, int mode) {
  std::vector<uint32_t> out;
  if (mode == TINYGLTF_MODE_TRIANGLES) return v;
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      const size_t odd = i % 2;
      out.insert(out.end(), {v[i], v[i + 1 + odd], v[i + 2 - odd]});
    } else {  // TRIANGLE_FAN
      out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
    }
  }
  return out;
}

WrapMode wrapMode(int gl) {
  if (gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return WrapMode::ClampToEdge;
  if (gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return WrapMode::MirroredRepeat;
  return WrapMode::Repeat;
}

int texture(Ctx& c, int gltfTexture, bool srgb, const std::string& field) {
  if (gltfTexture < 0) return -1;
  auto key = std::make_pair(gltfTexture, srgb);
  if (auto it = c.textureIds.find(key); it != c.textureIds.end()) return it->second;
  const auto& m = c.model;
  if (gltfTexture >= int(m.textures.size()))
    throw InputError(c.path, field, "texture index out of range");
  const tinygltf::Texture& t = m.textures[gltfTexture];
  if (t.source < 0 || t.source >= int(m.images.size()))
    throw InputError(c.path, field, "texture has no valid image source");
  const tinygltf::Image& img = m.images[t.source];
  if (img.image.empty() || img.width <= 0 || img.height <= 0 || img.component < 1)
    throw InputError(c.path, field, "image '" + img.uri + "' could not be loaded");
  if (img.bits != 8) throw InputError(c.path, field, "only 8-bit images are supported");
  Buffer rgba(img.width, img.height, 4, 1.0f);
  for (size_t i = 0; i < rgba.pixelCount(); ++i)
    for (int k = 0; k < std::min(img.component, 4); ++k)
      rgba.data[i * 4 + k] = img.image[i * img.component + k] / 255.0f;
  if (img.component < 3)  // grey (+alpha): replicate
    for (size_t i = 0; i < rgba.pixelCount(); ++i) {
      float a = img.component == 2 ? rgba.data[i * 4 + 1] : 1.0f;
      rgba.data[i * 4 + 1] = rgba.data[i * 4 + 2] = rgba.data[i * 4];
      rgba.data[i * 4 + 3] = a;
    }
  Texture tex = textureFromImage(img.uri.empty() ? img.name : img.uri, std::move(rgba), srgb);
  if (t.sampler >= 0 && t.sampler < int(m.samplers.size())) {
    tex.wrapS = wrapMode(m.samplers[t.sampler].wrapS);
    tex.wrapT = wrapMode(m.samplers[t.sampler].wrapT);
  }
  int id = c.scene.addTexture(std::move(tex));
  c.textureIds[key] = id;
  return id;
}

double extNumber(const tinygltf::ExtensionMap& ext, const char* name, const char* key, double def) {
  auto it = ext.find(name);
  if (it == ext.end() || !it->second.Has(key)) return def;
  const auto& v = it->second.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : def;
}

Material convertMaterial(Ctx& c, int index) {
  const tinygltf::Material& gm = c.model.materials[index];
  const std::string field = "materials[" + std::to_string(index) + "]";
  const auto& pbr = gm.pbrMetallicRoughness;
  Material m;
  m.name = gm.name.empty() ? field : gm.name;
  Vec3 base{float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
            float(pbr.baseColorFactor[2])};
  float metal = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
  float rough = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
  // Metallic-roughness -> Blinn-Phong (see docs/scene-format.md).
  BlinnPhongTerms bp = fromMetallicRoughness(base, metal, rough);
  m.diffuse = bp.diffuse;
  m.ambient = m.diffuse;
  m.specular = bp.specular;
  m.specularExponent = bp.exponent;
  m.reflectivity = bp.reflectivity;
  m.baseColor = base;
  m.metallic = metal;
  m.roughness = rough;
  m.diffuseOpacity = float(pbr.baseColorFactor[3]);
  float strength =
      float(extNumber(gm.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0));
  if (gm.emissiveFactor.size() == 3)
    m.emission = Vec3(float(gm.emissiveFactor[0]), float(gm.emissiveFactor[1]),
                      float(gm.emissiveFactor[2])) *
                 strength;
  m.ior = float(extNumber(gm.extensions, "KHR_materials_ior", "ior", 1.5));
  float transmission =
      float(extNumber(gm.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0));
  m.opacity = 1.0f - std::clamp(transmission, 0.0f, 1.0f);
  if (gm.alphaMode == "MASK") {
    m.alphaMode = AlphaMode::Mask;
    m.alphaCutoff = float(gm.alphaCutoff);
  } else if (gm.alphaMode == "BLEND") {
    m.alphaMode = AlphaMode::Blend;
    m.opacity = std::min(m.opacity, m.diffuseOpacity);
  } else if (gm.alphaMode != "OPAQUE" && !gm.alphaMode.empty()) {
    throw InputError(c.path, field + ".alphaMode", "unknown value '" + gm.alphaMode + "'");
  }
  m.doubleSided = gm.doubleSided;
  m.diffuseTexture = texture(c, pbr.baseColorTexture.index, true, field + ".baseColorTexture");
  m.emissionTexture = texture(c, gm.emissiveTexture.index, true, field + ".emissiveTexture");
  m.normalTexture = texture(c, gm.normalTexture.index, false, field + ".normalTexture");
  m.normalScale = float(gm.normalTexture.scale);
  m.metallicRoughnessTexture =
      texture(c, pbr.metallicRoughnessTexture.index, false, field + ".metallicRoughnessTexture");
  m.occlusionTexture = texture(c, gm.occlusionTexture.index, false, field + ".occlusionTexture");
  m.occlusionStrength = std::clamp(float(gm.occlusionTexture.strength), 0.0f, 1.0f);
  // KHR_texture_transform on the base colour texture sets the material's tiling/offset.
  auto tt = pbr.baseColorTexture.extensions.find("KHR_texture_transform");
  if (tt != pbr.baseColorTexture.extensions.end()) {
    const auto& v = tt->second;
    if (v.Has("offset") && v.Get("offset").ArrayLen() == 2)
      m.offset = {float(v.Get("offset").Get(0).GetNumberAsDouble()),
                  float(v.Get("offset").Get(1).GetNumberAsDouble())};
    if (v.Has("scale") && v.Get("scale").ArrayLen() == 2)
      m.tiling = {float(v.Get("scale").Get(0).GetNumberAsDouble()),
                  float(v.Get("scale").Get(1).GetNumberAsDouble())};
    if (v.Has("rotation") && v.Get("rotation").IsNumber())
      m.uvRotation = float(v.Get("rotation").GetNumberAsDouble());
  }
  if (!isFinite(m.emission) || !isFinite(m.diffuse) || !std::isfinite(m.ior))
    throw InputError(c.path, field, "non-finite material value");
  return m;
}

Mat4 nodeMatrix(const Ctx& c, const tinygltf::Node& n, int index) {
  Mat4 r;
  const std::string field = "nodes[" + std::to_string(index) + "]";
  if (n.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i) r.m[i % 4][i / 4] = float(n.matrix[i]);  // column-major
  } else {
    Vec3 t(0.0f), s(1.0f);
    Vec4 q(0, 0, 0, 1);
    if (n.translation.size() == 3)
      t = {float(n.translation[0]), float(n.translation[1]), float(n.translation[2])};
    if (n.scale.size() == 3) s = {float(n.scale[0]), float(n.scale[1]), float(n.scale[2])};
    if (n.rotation.size() == 4)
      q = {float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]), float(n.rotation[3])};
    r = Mat4::translate(t) * Mat4::fromQuaternion(q) * Mat4::scale(s);
  }
  for (auto& row : r.m)
    for (float v : row)
      if (!std::isfinite(v)) throw InputError(c.path, field, "transform is NaN or infinite");
  return r;
}

void addPrimitive(Ctx& c, const tinygltf::Mesh& gmesh, int meshIndex, size_t primIndex,
                  const Mat4& world, std::map<int, int>& materialIds, int& defaultMaterial) {
  const tinygltf::Primitive& p = gmesh.primitives[primIndex];
  const std::string field =
      "meshes[" + std::to_string(meshIndex) + "].primitives[" + std::to_string(primIndex) + "]";
  const int mode = p.mode == -1 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    if (mode < 0 || mode > TINYGLTF_MODE_TRIANGLE_FAN)
      throw InputError(c.path, field + ".mode", "unknown mode " + std::to_string(mode));
    ++c.scene.stats.skippedPrimitives;  // points and lines: nothing to shade
    return;
  }
  auto pos = p.attributes.find("POSITION");
  if (pos == p.attributes.end()) throw InputError(c.path, field, "no POSITION attribute");
  // Attribute values from the accessors, or from the Draco stream that replaces them.
  std::map<std::string, std::vector<float>> values;
  std::vector<uint32_t> sequence;
  bool indexed = p.indices >= 0;
  const std::pair<const char*, int> wanted[] = {
      {"POSITION", 3}, {"NORMAL", 3}, {"TEXCOORD_0", 2}, {"TANGENT", 4}};
  auto draco = p.extensions.find("KHR_draco_mesh_compression");
  if (draco != p.extensions.end()) {
    const std::string df = field + ".extensions.KHR_draco_mesh_compression";
    const tinygltf::Value& ext = draco->second;
    if (!ext.Has("bufferView") || !ext.Get("bufferView").IsInt() || !ext.Has("attributes") ||
        !ext.Get("attributes").IsObject())
      throw InputError(c.path, df, "needs a bufferView and an attributes object");
    const tinygltf::Value& ids = ext.Get("attributes");
    std::map<std::string, std::pair<int, int>> request;
    for (const auto& [name, comps] : wanted)
      if (p.attributes.count(name) && ids.Has(name) && ids.Get(name).IsInt())
        request[name] = {ids.Get(name).GetNumberAsInt(), comps};
    if (!request.count("POSITION")) throw InputError(c.path, df, "no POSITION attribute id");
    size_t stride = 0;
    const int view = ext.Get("bufferView").GetNumberAsInt();
    const size_t length = view >= 0 && view < int(c.model.bufferViews.size())
                              ? c.model.bufferViews[size_t(view)].byteLength
                              : 0;
    const unsigned char* bytes = viewBytes(c, view, 0, length, 1, &stride, df + ".bufferView");
    DracoPrimitive d = decodeDracoPrimitive(bytes, length, request, c.path, df);
    values = std::move(d.attributes);
    sequence = std::move(d.indices);
    indexed = true;
  } else {
    for (const auto& [name, comps] : wanted)
      if (auto it = p.attributes.find(name); it != p.attributes.end())
        values[name] = readAccessor(c, it->second, comps, field + "." + name);
  }
  Mesh mesh;
  const std::vector<float>& v = values["POSITION"];
  for (size_t i = 0; i < v.size() / 3; ++i)
    mesh.positions.push_back({v[3 * i], v[3 * i + 1], v[3 * i + 2]});
  const size_t n = mesh.positions.size();
  for (const auto& [name, comps] : wanted) {
    if (!values.count(name) || std::string(name) == "POSITION") continue;
    const std::vector<float>& a = values[name];
    if (a.size() / size_t(comps) != n)
      throw InputError(c.path, field + "." + name, "count differs from POSITION");
    for (size_t i = 0; i < n; ++i) {
      const float* e = &a[i * size_t(comps)];
      if (comps == 2) mesh.uvs.push_back({e[0], e[1]});
      if (comps == 3) mesh.normals.push_back({e[0], e[1], e[2]});
      if (comps == 4) mesh.tangents.push_back({e[0], e[1], e[2], e[3] < 0 ? -1.0f : 1.0f});
    }
  }
  if (draco == p.extensions.end() && indexed) sequence = readIndices(c, p.indices, n);
  if (!indexed)
    for (uint32_t i = 0; i < n; ++i) sequence.push_back(i);
  mesh.indices = trianglesFromTopology(sequence, mode);
  if (mesh.indices.size() % 3) throw InputError(c.path, field, "index count not a multiple of 3");
  c.scene.stats.degenerateTriangles += removeDegenerateTriangles(mesh);
  if (mesh.indices.empty()) return;
  int material;
  if (p.material >= 0) {
    if (p.material >= int(c.model.materials.size()))
      throw InputError(c.path, field + ".material", "material index out of range");
    auto it = materialIds.find(p.material);
    if (it == materialIds.end())
      it = materialIds.emplace(p.material, c.scene.addMaterial(convertMaterial(c, p.material)))
               .first;
    material = it->second;
  } else {
    if (defaultMaterial < 0) defaultMaterial = c.scene.addMaterial(Material{});
    material = defaultMaterial;
  }
  // glTF: a normal-mapped mesh without TANGENT gets MikkTSpace tangents (spec 3.7.2.1).
  if (c.scene.materials[size_t(material)].normalTexture >= 0 && mesh.tangents.empty() &&
      mesh.uvs.size() == mesh.positions.size()) {
    if (mesh.normals.size() != mesh.positions.size()) computeNormals(mesh);
    for (Vec3& nrm : mesh.normals) nrm = length(nrm) > 0 ? normalize(nrm) : Vec3(0, 1, 0);
    computeMikkTSpaceTangents(mesh);
  }
  std::string name = gmesh.name.empty() ? "mesh" + std::to_string(meshIndex) : gmesh.name;
  if (gmesh.primitives.size() > 1) name += "/" + std::to_string(primIndex);
  int obj = c.scene.addObject(name, c.scene.addMesh(std::move(mesh)), material);
  c.scene.objects[obj].parent = world;
}

void addLight(Ctx& c, int lightIndex, const Mat4& world) {
  const std::string field = "KHR_lights_punctual.lights[" + std::to_string(lightIndex) + "]";
  if (lightIndex < 0 || lightIndex >= int(c.model.lights.size()))
    throw InputError(c.path, field, "light index out of range");
  const tinygltf::Light& gl = c.model.lights[lightIndex];
  Light l;
  l.name = gl.name;
  if (gl.color.size() == 3) l.color = {float(gl.color[0]), float(gl.color[1]), float(gl.color[2])};
  l.intensity = float(gl.intensity);
  l.range = float(gl.range);
  l.position = world.transformPoint({0, 0, 0});
  l.direction = normalize(world.transformVector({0, 0, -1}));
  if (gl.type == "directional") {
    l.type = LightType::Directional;  // lux == W/m^2 in Tandem's units
  } else if (gl.type == "point") {
    l.type = LightType::Point;  // candela == W/sr
  } else if (gl.type == "spot") {
    l.type = LightType::Spot;
    l.innerConeDeg = degrees(float(gl.spot.innerConeAngle));
    l.outerConeDeg = degrees(float(gl.spot.outerConeAngle));
  } else {
    throw InputError(c.path, field + ".type", "unknown light type '" + gl.type + "'");
  }
  if (!std::isfinite(l.intensity) || l.intensity < 0)
    throw InputError(c.path, field + ".intensity", "must be finite and >= 0");
  c.scene.lights.push_back(l);
}

// tinygltf's own reader sizes its buffer from tellg(): a buffer or image URI naming a directory
// (or anything that is not a regular file) made it allocate 2^63 bytes (found by fuzz_gltf). Read
// only regular files, of a size we could hold.
bool readFileCallback(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                      void*) {
  const std::string problem = readRegularFile(path, *out);
  if (!problem.empty() && err) *err += problem + ": " + path + "\n";
  return problem.empty();
}

}  // namespace

Scene loadGltf(const std::string& path) {
  const GltfSource src = preflightGltf(path);
  tinygltf::TinyGLTF loader;
  tinygltf::FsCallbacks callbacks{&tinygltf::FileExists, &tinygltf::ExpandFilePath,
                                  &readFileCallback, &tinygltf::WriteWholeFile, nullptr};
  loader.SetFsCallbacks(callbacks);
  tinygltf::Model model;
  std::string err, warn;
  const std::string baseDir = fs::absolute(path).parent_path().string();
  bool ok = src.binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, src.bytes.data(),
                                                     unsigned(src.bytes.size()), baseDir)
                       : loader.LoadASCIIFromString(&model, &err, &warn,
                                                    reinterpret_cast<const char*>(src.bytes.data()),
                                                    unsigned(src.bytes.size()), baseDir);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n')) err.pop_back();
    throw InputError(path, "", "cannot parse glTF: " + (err.empty() ? "unknown error" : err));
  }
  for (const std::string& e : model.extensionsRequired)
    if (!kSupportedExtensions.count(e))
      throw InputError(path, "extensionsRequired", "unsupported required extension '" + e + "'");
  Scene s;
  s.name = fs::path(path).stem().string();
  s.stats.sources.push_back(path);
  Ctx c{path, model, s, {}};
  std::map<int, int> materialIds;
  int defaultMaterial = -1;
  std::set<int> visiting;
  std::function<void(int, const Mat4&, int)> visit = [&](int n, const Mat4& parent, int depth) {
    if (n < 0 || n >= int(model.nodes.size()))
      throw InputError(path, "nodes", "node index " + std::to_string(n) + " out of range");
    if (depth > 256 || visiting.count(n))
      throw InputError(path, "nodes[" + std::to_string(n) + "]", "node hierarchy has a cycle");
    visiting.insert(n);
    const tinygltf::Node& node = model.nodes[n];
    Mat4 world = parent * nodeMatrix(c, node, n);
    if (node.mesh >= 0) {
      if (node.mesh >= int(model.meshes.size()))
        throw InputError(path, "nodes[" + std::to_string(n) + "].mesh", "mesh index out of range");
      for (size_t p = 0; p < model.meshes[node.mesh].primitives.size(); ++p)
        addPrimitive(c, model.meshes[node.mesh], node.mesh, p, world, materialIds, defaultMaterial);
    }
    if (node.camera >= 0 && !s.hasCamera) {
      if (node.camera >= int(model.cameras.size()))
        throw InputError(path, "nodes[" + std::to_string(n) + "].camera",
                         "camera index out of range");
      const tinygltf::Camera& cam = model.cameras[node.camera];
      s.camera.position = world.transformPoint({0, 0, 0});
      s.camera.lookAt = s.camera.position + normalize(world.transformVector({0, 0, -1}));
      s.camera.up = normalize(world.transformVector({0, 1, 0}));
      if (cam.type == "orthographic") {
        s.camera.projection = Projection::Orthographic;
        s.camera.orthoHeight = 2.0f * float(cam.orthographic.ymag);
        s.camera.nearPlane = float(cam.orthographic.znear);
        s.camera.farPlane = float(cam.orthographic.zfar);
      } else {
        s.camera.vfovDeg = degrees(float(cam.perspective.yfov));
        if (cam.perspective.znear > 0) s.camera.nearPlane = float(cam.perspective.znear);
      }
      s.hasCamera = true;
    }
    auto lp = node.extensions.find("KHR_lights_punctual");
    if (lp != node.extensions.end() && lp->second.Has("light"))
      addLight(c, lp->second.Get("light").GetNumberAsInt(), world);
    for (int child : node.children) visit(child, world, depth + 1);
    visiting.erase(n);
  };
  int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (!model.scenes.empty()) {
    if (sceneIndex >= int(model.scenes.size()))
      throw InputError(path, "scene", "default scene index out of range");
    for (int n : model.scenes[sceneIndex].nodes) visit(n, Mat4(), 0);
  } else {
    for (int n = 0; n < int(model.nodes.size()); ++n) visit(n, Mat4(), 0);
  }
  if (s.objects.empty())
    throw InputError(path, "",
                     s.stats.skippedPrimitives
                         ? "no triangle meshes (" + std::to_string(s.stats.skippedPrimitives) +
                               " point or line primitives skipped)"
                         : std::string("no triangle meshes"));
  validateScene(s, path);
  return s;
}

}  // namespace tandem
