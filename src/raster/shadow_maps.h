// Raster shadow maps: what decides shadows without rays — for pixels the heuristic did not select
// (the fallback production hybrids use) and, with a conservative map beside each, for classified
// shadows (classify: lit, shadowed, or left to a ray). One depth map per directional light
// (orthographic, over the scene's bounds), per spot light (its cone) and six per point light (a
// cube), drawn by the same rasterizer as the G-buffer. Casters that are not animated are drawn once
// (again only when lights or static geometry change); animated casters are drawn over a copy of
// that depth whenever they moved. A moving camera reuses the maps as they are.
#pragma once
#include <algorithm>
#include <memory>
#include <vector>

#include "raster/conservative_depth.h"
#include "raster/rasterizer.h"
#include "raster/shadow_lookup.h"
#include "scene/camera.h"
#include "scene/frame_scene.h"

namespace tandem {

// What classified shadows know of one light at one point before any ray: the light adds nothing
// there (culled: facing away, outside its cone or range, or too faint to matter), the maps are
// certain it arrives (lit) or is blocked by opaque casters (shadowed), or only a shadow ray can
// tell (traced).
enum class ShadowClass : uint8_t { Culled = 0, Lit = 1, Shadowed = 2, Traced = 3 };

// Every map face's texels together stay within this many (about 0.75 GiB of maps and their
// companions): a scene with many lights gets coarser maps instead of running out of memory.
constexpr double kMaxShadowTexels = 128.0 * 1024 * 1024;
// Texels a side of light l's faces for a map size of `resolution`. A directional light's one map
// spans the whole scene, so it gets twice the side; a cube's six faces (point lights, spots of
// 80 degrees or more) half the side, as together they cover what one spot map does.
int shadowFaceSize(const Light& l, int resolution);
// Whether light l's map is a cube of six faces (point lights, spots of 80 degrees or more).
bool cubeShadowMap(const Light& l);
// The map size (texels a side) `requested` becomes for the scene's shadow-casting lights: as
// asked, or smaller (a multiple of 32, at least 32) when the faces would exceed kMaxShadowTexels.
int budgetedShadowMapSize(const Scene& scene, int requested);

// Whether objects of material m go into the depth maps: it casts shadows and one of its
// surfaces lets less than half the light through, as a shadow ray weighs it ((1 - diffuse) x
// (1 - opacity) x transmission filter, averaged over RGB). A binary depth map can hold only
// all or nothing: this is the nearer of the two to the traced transmittance.
bool solidCaster(const Material& m);

// A device that draws and keeps the maps in place of the CPU (the GPU's compute rasterizer:
// passes/common/gpu_shadow_maps.h). ShadowMaps plans what to draw as it does for its own maps; the
// device draws it and answers the lookups (ShadowMaps' own classify and visibility are for maps
// the CPU drew).
class ShadowMapDevice {
 public:
  struct Job {
    size_t light = 0, face = 0;
    Camera camera;
    std::vector<uint8_t> casters;        // per object: drawn (empty: none)
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the texels made anew, [x0, x1) x [y0, y1)
    // Fresh: the face cleared and its static casters drawn (a copy kept when keepStatic).
    // Otherwise the static copy restored in the rectangle and the casters drawn over it.
    bool fresh = false;
  };
  virtual ~ShadowMapDevice() = default;
  // Records the jobs in order, then the texels of each job's rectangle that hold an opaque caster
  // (`opaqueCasters`, per object). `sweep`: objects moving while the shutter is open are drawn into
  // the conservative maps as their box over the shutter.
  // `solidCasters` (per object): drawn into the depth maps (the conservative maps take every
  // caster of a job).
  virtual void draw(const FrameScene& fs, const std::vector<Job>& jobs, bool keepStatic, bool sweep,
                    const std::vector<uint8_t>& opaqueCasters,
                    const std::vector<uint8_t>& solidCasters) = 0;
};

class ShadowMaps {
 public:
  // Maps drawn and kept by `device` from now on (everything drawn anew at the next update).
  void drawOn(std::unique_ptr<ShadowMapDevice> device);
  ShadowMapDevice* device() const { return device_.get(); }
  // Everything drawn anew at the next update (a device lost what it held).
  void invalidate();
  // Redraws what changed: everything for new lights, resolution or static geometry; the
  // animated casters over the static depth when only they moved. `resolution` as
  // budgetedShadowMapSize gives it. `wanted` (optional, per light): only these lights need maps
  // this frame (the lights that reach a surface in view, lightsInView); a light wanted for the
  // first time is drawn then, alone. Null: every light that casts shadows.
  void update(const FrameScene& fs, int resolution, const std::vector<uint8_t>* wanted = nullptr);
  // Lights that have maps now.
  int mappedLights() const { return mapped_; }
  // Fraction (0..1, 2x2 percentage-closer filtered) of light `i` reaching point p with unit
  // normal n; 1 for lights that cast no shadows or have no maps (not wanted), or where p lies
  // outside every map.
  float visibility(size_t i, Vec3 p, Vec3 n) const;
  // The same for up to 16 points (structure of arrays, 16 entries each) in one SIMD kernel:
  // out[k] = visibility(i, p[k], n[k]) for the lanes k < count with use[k] != 0 (equal up to
  // rounding at a tap's depth threshold).
  void visibilityBatch(size_t i, const float* px, const float* py, const float* pz, const float* nx,
                       const float* ny, const float* nz, const float* use, int count,
                       float* out) const;
  // Classified shadows: whether the maps decide light `i` at point p (geometric normal n, on
  // object `self`) without a ray. Lit when no caster can lie between p and the light (the
  // conservative map of the ray's texel holds nothing nearer than p beyond the receiver's own
  // slope); shadowed when the 3x3 texels around p all hold opaque, static casters well in front
  // of it; traced otherwise (an edge, a transparent or moving caster, a grazing light, p outside
  // the maps, a light that casts shadows but has no maps yet). Never returns Culled.
  ShadowClass classify(size_t i, Vec3 p, Vec3 n, int self) const;
  // The same for up to 8 points at once (their map lookups overlap): out[k] for the lanes k <
  // count with want[k].
  void classify(size_t i, int count, const Vec3* p, const Vec3* n, const int* self,
                const bool* want, ShadowClass* out) const;
  // Light i's map faces (none when it has none): each face's camera and, for maps the CPU drew,
  // its texels as classify and visibility read them (null for a device's maps).
  struct FaceView {
    const Camera* camera;
    int width, height;
    float texelPerDistance;
    const float* depth;                    // the map (reversed-Z)
    const ConservativeDepth::Texel* near;  // the conservative map
    const float* opaqueDepth;              // depth where an opaque static caster drew it, else 0
  };
  std::vector<FaceView> faceViews(size_t i) const;
  bool castsShadows(size_t i) const { return i < casts_.size() && casts_[i] != 0; }
  size_t lights() const { return faces_.size(); }
  // Changes whenever update() draws anything (unique across ShadowMaps objects): a device copy
  // made at one version is current while the version stays.
  uint64_t version() const { return version_; }
  int redraws() const { return redraws_; }              // full (static) redraws
  int movingRedraws() const { return movingRedraws_; }  // animated casters drawn again

 private:
  struct TexelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    TexelRect unite(const TexelRect& o) const {
      if (empty()) return o;
      if (o.empty()) return *this;
      return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
    }
  };
  struct Face {
    Camera camera;
    VisibilityBuffer map;            // depth and object are read (prim is scratch)
    std::vector<float> staticDepth;  // the static casters' depth, when animated ones exist
    std::vector<uint32_t> staticObject;
    ConservativeDepth near, staticNear;  // every caster a texel touches (classified shadows)
    std::vector<float> opaqueDepth;      // map depth where an opaque caster drew it, else 0
    TexelRect moving, dirty;  // where the moving casters were drawn; what the last redraw touched
    ShadowFace lookup{};      // what the batch kernel reads (depth: map's, at lookup)
    float texelPerDistance = 0;  // a texel's world width per unit distance (ortho: the width)
  };
  // Makes the faces of `lights` anew and draws their static casters (on the device: adds the
  // jobs).
  void drawStatic(const FrameScene& fs, const std::vector<uint8_t>& still, bool keepCopy,
                  const std::vector<size_t>& lights, std::vector<ShadowMapDevice::Job>* jobs);
  // The face of light i that sees p: the cube face of p's major axis, else the one map.
  const Face* faceFor(size_t i, Vec3 p) const;
  void markOpaque(Face& face, const TexelRect& r) const;
  // The texels the boxes cover in f (with a margin; all of f when one reaches behind the light).
  static TexelRect footprint(const Face& f, const std::vector<Bounds3>& boxes);
  // The casters of `casters` (per object) that go into the depth maps.
  std::vector<uint8_t> solidOf(const std::vector<uint8_t>& casters) const;
  // The static casters' maps back in r.
  static void restoreStatic(Face& f, const TexelRect& r);

  std::vector<std::vector<Face>> faces_;  // per light
  uint64_t geometryVersion_ = ~0ull, staticVersion_ = ~0ull;
  const Scene* scene_ = nullptr;
  std::vector<float> lightKey_;
  // Per object: its shadow is opaque and where the maps drew it (no transmission, no alpha
  // mask, casts shadows, still while the shutter is open). Only these make a pixel "shadowed".
  std::vector<uint8_t> opaqueCaster_;
  // Per object: drawn into the depth maps that visibility() filters (solidCaster): a caster
  // that lets most light through (glass) is left out, as a shadow ray passes it almost unhindered.
  std::vector<uint8_t> solidCaster_;
  bool sweep_ = false;          // the shutter was open when the conservative maps were drawn
  std::vector<uint8_t> casts_;  // per light: it casts shadows
  int resolution_ = 0, redraws_ = 0, movingRedraws_ = 0, mapped_ = 0;
  uint64_t version_ = 0;
  Rasterizer raster_;
  std::unique_ptr<ShadowMapDevice> device_;
};

}  // namespace tandem
