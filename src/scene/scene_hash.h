// A content hash of everything in a Scene that can change a rendered image (geometry, objects
// and their animation, materials, texture texels, lights, sky, camera path), for the reference
// image cache: an edited scene file, model or texture gets a new key.
#pragma once
#include "core/hash.h"
#include "scene/scene.h"

namespace tandem {

void hashScene(Hasher& h, const Scene& s);
void hashCamera(Hasher& h, const CameraDesc& c);

}  // namespace tandem
