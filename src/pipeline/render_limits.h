// The limits a render's settings must keep, checked alike wherever they come from (the CLI's
// options, Python's arguments): each failure an InputError naming the caller's field.
#pragma once
#include <string>

namespace tandem {

// Width and height in [1, 16384] (one eye), and buffers the machine can hold: a frame needs at
// least ~175 bytes a pixel (G-buffer, history, outputs), refused before anything is allocated.
void checkFrameSize(const std::string& source, const std::string& widthField,
                    const std::string& heightField, double width, double height, bool stereo);
struct Scene;

// What rendering a scene at a size needs, roughly, in bytes: the scene's own arrays, and per
// triangle its world-space copy and ray-tracing hierarchy (~160 bytes); the frame's buffers (as
// checkFrameSize); the shadow maps at their texel budget when a light casts shadows.
struct MemoryNeed {
  double geometry = 0, buffers = 0, shadowMaps = 0;
  double total() const { return geometry + buffers + shadowMaps; }
};
MemoryNeed memoryNeed(const Scene& scene, double width, double height, bool stereo);
// An InputError naming the scene (field `field` of `source`) and what it needs, part by part,
// when that exceeds 90 % of `haveBytes` (default: the machine's physical memory).
void checkSceneFits(const std::string& source, const std::string& field, const Scene& scene,
                    double width, double height, bool stereo, double haveBytes = 0);
// Seconds the shutter stays open: finite, in [0, 1000].
void checkShutter(const std::string& source, const std::string& field, double seconds);
// A reference's samples per pixel: in [1, 2^20].
void checkSpp(const std::string& source, const std::string& field, double spp);
// A scene time in seconds: finite.
void checkTime(const std::string& source, const std::string& field, double seconds);

}  // namespace tandem
