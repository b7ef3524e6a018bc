#include "scene/obj_writer.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>

#include "core/image_io.h"
#include "scene/frame_scene.h"

namespace tandem {

namespace {
// OBJ names end at whitespace; keep them to one safe token.
std::string token(const std::string& name) {
  std::string t;
  for (char c : name)
    t += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ? c : '_';
  return t.empty() ? "unnamed" : t;
}
}  // namespace

size_t writeObj(const Scene& s, const std::string& objPath, float time) {
  namespace fs = std::filesystem;
  const fs::path mtlPath = fs::path(objPath).replace_extension(".mtl");
  FrameScene frame;
  frame.update(s, time, time);
  std::ostringstream mtl, obj;
  mtl.precision(6);
  for (size_t m = 0; m < s.materials.size(); ++m) {
    const Material& mat = s.materials[m];
    const int illum = mat.opacity < 1 ? 7 : mat.reflectivity > 0 ? 5 : 2;
    // Textures are not written: a textured colour becomes its mean texel times the factor.
    Vec3 kd = mat.diffuse;
    if (mat.diffuseTexture >= 0) {
      const Buffer& t = s.textures[size_t(mat.diffuseTexture)].texels;
      Vec3 sum(0.0f);
      for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x) sum += t.rgb(x, y);
      kd = kd * sum / float(std::max<size_t>(t.pixelCount(), 1));
    }
    mtl << "newmtl m" << m << "_" << token(mat.name) << "\nKd " << kd.x << " " << kd.y << " "
        << kd.z << "\nKs " << mat.specular.x << " " << mat.specular.y << " " << mat.specular.z
        << "\nNs " << mat.specularExponent << "\nKe " << mat.emission.x << " " << mat.emission.y
        << " " << mat.emission.z << "\nNi " << mat.ior << "\nd " << mat.opacity << "\nillum "
        << illum << "\n\n";
  }
  obj.precision(7);
  obj << "# Tandem scene '" << s.name << "' at t = " << time << " s (world space)\nmtllib "
      << mtlPath.filename().string() << "\n";
  size_t base = 1, triangles = 0;
  for (size_t o = 0; o < s.objects.size(); ++o) {
    const Object& ob = s.objects[o];
    const Mesh& mesh = s.meshes[ob.mesh];
    const FrameObject& fo = frame.objects[o];
    const Material& mat = s.materials[ob.material];
    obj << "o " << token(ob.name.empty() ? "object" + std::to_string(o) : ob.name) << "\nusemtl m"
        << ob.material << "_" << token(mat.name) << "\n";
    for (const Vec3& p : fo.positions) obj << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (const Vec3& n : fo.normals) obj << "vn " << n.x << " " << n.y << " " << n.z << "\n";
    for (const Vec2& t : mesh.uvs) obj << "vt " << t.x << " " << 1.0f - t.y << "\n";
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      obj << "f";
      for (int k = 0; k < 3; ++k) {
        const size_t i = base + mesh.indices[3 * t + size_t(k)];
        obj << " " << i << "/" << i << "/" << i;
      }
      obj << "\n";
    }
    base += fo.positions.size();
    triangles += mesh.triangleCount();
  }
  writeTextFile(mtlPath.string(), mtl.str());
  writeTextFile(objPath, obj.str());
  return triangles;
}

}  // namespace tandem
