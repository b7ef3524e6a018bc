// KHR_draco_mesh_compression: a primitive's triangles and attributes decoded from its Draco
// stream with Debian's libdraco, every index and count checked (the stream is untrusted input).
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace tandem {

struct DracoPrimitive {
  size_t points = 0;
  std::vector<uint32_t> indices;  // three per triangle, each < points
  // Per requested glTF attribute name: `components` floats per point.
  std::map<std::string, std::vector<float>> attributes;
};

// `attributes`: glTF attribute name -> (Draco unique id, components wanted). Throws InputError
// naming `path` and `field` when the stream does not decode or lacks what it promises.
DracoPrimitive decodeDracoPrimitive(const unsigned char* data, size_t size,
                                    const std::map<std::string, std::pair<int, int>>& attributes,
                                    const std::string& path, const std::string& field);

}  // namespace tandem
