// Reflection probes: the stand-in production hybrids use for reflections and refractions they do
// not ray trace. For each object that needs one, a small cube map of the scene seen from the
// object's centre (the object itself left out), rasterized, resolved and shaded by the one
// shading function (lights unshadowed; the sky behind). A mirror ball looks up its reflected
// direction; glass looks up the direction its ray leaves by, refracted in and out of the
// object's bounding sphere. Probes do not depend on the camera: they are redrawn only when the
// lights change, an object that is not animated changes, or an animated object the probe shows
// has moved by half a texel as seen from the probe's centre since it was drawn.
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "core/buffer.h"
#include "raster/rasterizer.h"
#include "scene/frame_scene.h"
#include "shading/blinn_phong.h"

namespace tandem {

// A device that draws and keeps probes in place of the CPU (the GPU's compute rasterizer and
// resolve: gpu_reflection_probes.h). ReflectionProbes chooses what to draw as for its own probes;
// the device draws it, and the lookups happen there.
class ProbeDevice {
 public:
  virtual ~ProbeDevice() = default;
  // Draws object `object`'s probe: six size x size faces seen by `cameras`, of the objects
  // `others` marks, shaded as ReflectionProbes::draw shades them.
  virtual void draw(const FrameScene& fs, int object, const Camera* cameras, int size,
                    const std::vector<uint8_t>& others) = 0;
  virtual void release(int object) = 0;  // its probe freed
};

class ReflectionProbes {
 public:
  // Probes drawn and kept by `device` from now on (everything drawn anew at the next update).
  void drawOn(std::unique_ptr<ProbeDevice> device);
  ProbeDevice* device() const { return device_.get(); }
  // Every probe drawn anew when next wanted (a device lost what it held).
  void invalidate() { probes_.clear(); }
  // Makes sure every object with wanted[o] != 0 has a probe of `size`^2 faces: missing ones are
  // drawn now; ones whose geometry changed since (animated scenes) are redrawn, oldest first,
  // at most `refresh` a frame (what games do: probes trail moving objects by a few frames).
  // Probes beyond `capacity` are freed, the longest unwanted first. Returns the probes drawn.
  int update(const FrameScene& fs, const ShadingContext& shading,
             const std::vector<uint8_t>& wanted, int size, int refresh, size_t capacity);
  // Updates so far (0: none yet, the first frame to come).
  uint64_t updates() const { return updates_; }
  // Radiance arriving at object o's centre from unit direction d (bilinear within a face); the
  // sky where o has no probe.
  Vec3 lookup(const Scene& scene, int object, Vec3 d) const;
  // Radiance seen from point p (near object o) along unit direction d, parallax-corrected
  // (Lagarde 2012): the ray is followed to the box `proxy` (the scene's bounds) and the probe is
  // looked up towards where it leaves, so a floor or a wall appears where it would from p.
  Vec3 lookupFrom(const Scene& scene, int object, Vec3 p, Vec3 d, const Bounds3& proxy) const;
  // The direction a ray entering object o at p along t (already refracted in) leaves by: out
  // through the object's bounding sphere, refracted (eta = ior inside / outside), or reflected
  // back in on total internal reflection (then looked up as it is).
  // `exit` receives the point it leaves from.
  Vec3 exitDirection(int object, Vec3 p, Vec3 t, float eta, Vec3& exit) const;

  // Object o's probe (size 0: it has none); faces null for a device's probes.
  struct ProbeView {
    int size = 0;
    Vec3 centre;
    float radius = 0;
    const Camera* cameras = nullptr;  // the six faces'
    const Buffer* faces = nullptr;    // six, size x size RGB
  };
  ProbeView probe(size_t o) const;
  size_t objects() const { return probes_.size(); }
  // Changes whenever update() draws or frees a probe (unique across ReflectionProbes objects).
  uint64_t version() const { return version_; }

 private:
  struct Probe {
    uint64_t version = ~0ull;        // geometry version drawn for
    uint64_t staticVersion = ~0ull;  // static geometry version drawn for
    // The animated objects drawn into it and their bounds then: the probe is out of date once
    // one of them has visibly moved.
    std::vector<std::pair<int, Bounds3>> movers;
    uint64_t drawn = 0;   // update() call it was drawn in (the oldest is refreshed first)
    uint64_t wanted = 0;  // update() call that last wanted it (the oldest is freed first)
    Vec3 centre;
    float radius = 0;
    int size = 0;
    std::vector<Camera> cameras;  // the six faces
    std::vector<Buffer> faces;    // size x size radiance each
  };
  void draw(const FrameScene& fs, const ShadingContext& shading, int object, int size, Probe& p);
  // Whether what probe p shows changed since it was drawn (by more than half a texel).
  static bool outdated(const FrameScene& fs, const Probe& p);

  std::vector<Probe> probes_;  // per object
  uint64_t updates_ = 0, version_ = 0;
  std::vector<float> lightKey_;
  Rasterizer raster_;
  VisibilityBuffer vis_;
  std::unique_ptr<ProbeDevice> device_;
};

}  // namespace tandem
