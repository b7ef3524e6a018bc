// Writes a scene, evaluated at a time, as Wavefront OBJ + MTL in world space (one `o` group per
// object, shared positions/normals/uvs per object, materials by name with Kd, Ks, Ns, Ke, Ni, d
// and illum). Textures and lights are not written (OBJ has no lights; pass them to the other
// renderer on its command line). Used to give another renderer — Embree's path tracer
// tutorial — exactly the geometry Tandem renders.
#pragma once
#include <string>

#include "scene/scene.h"

namespace tandem {

// Writes `objPath` and the .mtl beside it (same stem); throws InputError when a file cannot be
// written. Returns the number of triangles written.
size_t writeObj(const Scene& s, const std::string& objPath, float time = 0.0f);

}  // namespace tandem
