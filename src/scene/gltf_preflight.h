// What tinygltf cannot be trusted to say about a glTF file, checked on its JSON before tinygltf
// parses it: a glTF 1.0 file is named as such (tinygltf says "asset object not found" or "no
// triangle meshes"), and primitives compressed with KHR_draco_mesh_compression lose their
// bufferView-less "indices" (which tinygltf, built without Draco, refuses) so that
// gltf_draco.cpp can decode them.
#pragma once
#include <string>
#include <vector>

namespace tandem {

struct GltfSource {
  bool binary = false;
  bool usesDraco = false;
  // The file as tinygltf should read it: unchanged unless Draco primitives were rewritten.
  std::vector<unsigned char> bytes;
};

// Reads a regular file of at most 16 GiB into `out`: "" on success, else the problem ("file
// not found" for anything that is not a regular file, e.g. a folder a URI decodes to). Used for
// the glTF file and, as tinygltf's reader, for its buffers and images.
std::string readRegularFile(const std::string& path, std::vector<unsigned char>& out);

// Reads `path` (.gltf or .glb) and checks it; throws InputError naming the file and field.
GltfSource preflightGltf(const std::string& path);

}  // namespace tandem
