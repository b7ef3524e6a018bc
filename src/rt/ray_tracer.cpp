#include "rt/ray_tracer.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <tbb/task_arena.h>

#include "shading/surface_resolve.h"

namespace tandem {

// Per-geometry data for filter callbacks.
struct GeometryInfo {
  const FrameScene* frame;
  int object;
  bool singleSided, alphaMask;
};

namespace {

// One shadow ray's Listing 8b state: its attenuation so far, and the surfaces already counted (a
// ray through a shared edge reports both triangles at the same distance, which must attenuate
// once).
struct ShadowLane {
  Vec3 transmittance{1.0f};
  struct Counted {
    unsigned geom;
    float t;
  } counted[8];
  int countedN = 0;
};

// Ray counters, a power of two known at compile time: a thread's slot is a mask, not a
// division per ray.
constexpr size_t kRayCounters = 64;

// Context passed to filter callbacks (Embree's documented pattern of extending the context).
struct QueryContext {
  RTCIntersectContext ctx;
  const FrameScene* frame;
  // Non-null: shadow rays accumulating Listing 8b's attenuation, indexed by the ray's id (its
  // lane: Embree may call the filter with single rays out of a packet).
  ShadowLane* shadow = nullptr;
  bool texturedShadows = true;  // the occluder's textured diffuse colour (else the base colour)
};

void errorCallback(void*, RTCError code, const char* str) {
  std::fprintf(stderr, "embree error %d: %s\n", int(code), str ? str : "");
}

// Camera queries that mimic the rasterizer reject hits on the back of single-sided surfaces. A
// context filter (set only on those queries) rather than a geometry filter, so every other ray
// runs without a callback.
void cullBackfaceHit(const RTCFilterFunctionNArguments* args) {
  const auto* info = static_cast<const GeometryInfo*>(args->geometryUserPtr);
  if (!info->singleSided) return;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    Vec3 ng{RTCHitN_Ng_x(args->hit, args->N, i), RTCHitN_Ng_y(args->hit, args->N, i),
            RTCHitN_Ng_z(args->hit, args->N, i)};
    Vec3 d{RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
           RTCRayN_dir_z(args->ray, args->N, i)};
    // Embree's Ng points out of the counter-clockwise (front) face, against a front-facing ray.
    if (dot(ng, d) >= 0) args->valid[i] = 0;
  }
}

// Rejects hits on transparent texels of alpha-masked materials and accumulates Listing 8b's
// shadow attenuation.
void filterHit(const RTCFilterFunctionNArguments* args) {
  const auto* info = static_cast<const GeometryInfo*>(args->geometryUserPtr);
  const auto* qc = reinterpret_cast<const QueryContext*>(args->context);
  const Scene& scene = *info->frame->scene;
  const Material& mat = scene.materials[scene.objects[info->object].material];
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    RTCHitN* hit = args->hit;
    RTCRayN* ray = args->ray;
    if (info->alphaMask) {
      float u = RTCHitN_u(hit, args->N, i), v = RTCHitN_v(hit, args->N, i);
      unsigned prim = RTCHitN_primID(hit, args->N, i);
      if (surfaceAlpha(*info->frame, info->object, int(prim), u, v) < mat.alphaCutoff) {
        args->valid[i] = 0;
        continue;
      }
    }
    if (qc->shadow) {
      // Listing 8b: occluders that cast shadows attenuate by transparency x (1 - diffuse); the
      // ray ends once nothing passes, otherwise the hit is ignored and traversal goes on.
      // (The BVH is built without spatial splits, so each triangle is reported once.)
      if (!mat.castsShadows) {
        args->valid[i] = 0;
        continue;
      }
      ShadowLane& q = qc->shadow[RTCRayN_id(ray, args->N, i)];
      unsigned geom = RTCHitN_geomID(hit, args->N, i);
      float tHit = RTCRayN_tfar(ray, args->N, i);
      bool duplicate = false;
      for (int k = 0; k < std::min(q.countedN, 8); ++k)
        duplicate |= q.counted[k].geom == geom &&
                     std::abs(q.counted[k].t - tHit) <= 1e-5f * std::max(1.0f, tHit);
      if (duplicate) {
        args->valid[i] = 0;
        continue;
      }
      q.counted[q.countedN++ % 8] = {geom, tHit};  // a ring of the 8 most recent surfaces
      Vec3& t = q.transmittance;
      Vec3 diffuse = mat.diffuse;
      float opacity = mat.opacity;
      if (qc->texturedShadows && mat.opacity < 1.0f) {
        // The surface as the G-buffer would hold it (textures, metallic-roughness), from Embree's
        // own distance and barycentrics.
        const float tuv[3] = {tHit, RTCHitN_u(hit, args->N, i), RTCHitN_v(hit, args->N, i)};
        const Vec3 o{RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i),
                     RTCRayN_org_z(ray, args->N, i)};
        const Vec3 d{RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i),
                     RTCRayN_dir_z(ray, args->N, i)};
        const SurfaceSample sh =
            resolveSurface(*info->frame, int(info->object), int(RTCHitN_primID(hit, args->N, i)), o,
                           d, RTCRayN_time(ray, args->N, i), tuv);
        diffuse = sh.diffuse;
        opacity = sh.opacity;
      }
      t = t * (Vec3(1.0f) - vmin(diffuse, Vec3(1.0f))) * (1.0f - opacity) * mat.transmissionFilter;
      if (maxComponent(t) > 0.0f) args->valid[i] = 0;
    }
  }
}

}  // namespace

RayTracer::RayTracer() : rays_(new RayCounter[kRayCounters]), rayCounters_(kRayCounters) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create Embree device");
  rtcSetDeviceErrorFunction(device_, errorCallback, nullptr);
}

RayTracer::~RayTracer() {
  if (scene_) rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

bool RayTracer::update(const FrameScene& fs) {
  if (scene_ && frame_ == &fs && builtVersion_ == fs.geometryVersion) return false;
  if (scene_) rtcReleaseScene(scene_);
  geometryInfo_.clear();
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);  // back-face culling
  const Scene& scene = *fs.scene;
  for (size_t o = 0; o < fs.objects.size(); ++o) {
    const Mesh& mesh = scene.meshes[scene.objects[o].mesh];
    const Material& mat = scene.materials[scene.objects[o].material];
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Shared buffers: Embree reads our arrays in place (it needs 16 bytes of padding after the
    // last vertex, which std::vector<Vec3> capacity does not guarantee, so copy vertices).
    // Objects moving while the shutter is open get one vertex buffer per time step; Embree
    // interpolates linearly between them at each ray's time.
    const FrameObject& fo = fs.objects[o];
    const bool moving = fo.stepPositions.size() >= 2;
    if (moving) rtcSetGeometryTimeStepCount(g, unsigned(fo.stepPositions.size()));
    for (size_t k = 0; k < (moving ? fo.stepPositions.size() : 1); ++k) {
      const std::vector<Vec3>& p = moving ? fo.stepPositions[k] : fo.positions;
      float* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, unsigned(k), RTC_FORMAT_FLOAT3, sizeof(Vec3), p.size()));
      std::memcpy(vb, p.data(), p.size() * sizeof(Vec3));
    }
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(),
                               0, 3 * sizeof(uint32_t), mesh.triangleCount());
    geometryInfo_.push_back(std::make_unique<GeometryInfo>(
        GeometryInfo{&fs, int(o), !mat.doubleSided, mat.alphaMode == AlphaMode::Mask}));
    GeometryInfo* info = geometryInfo_.back().get();
    rtcSetGeometryUserData(g, info);
    if (info->alphaMask) rtcSetGeometryIntersectFilterFunction(g, filterHit);
    // Occlusion queries filter only where a hit may not end the shadow ray: transparent,
    // alpha-masked or non-shadow-casting materials; an opaque caster's first hit is final and
    // needs no callback.
    if (mat.opacity < 1 || !mat.castsShadows || info->alphaMask)
      rtcSetGeometryOccludedFilterFunction(g, filterHit);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene_, g, unsigned(o));
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene_);
  frame_ = &fs;
  builtVersion_ = fs.geometryVersion;
  return true;
}

namespace {
// Thread slots are unique within an arena; the modulo only matters past 64 threads, where the
// atomics keep sharing correct (and per-thread differences approximate).
size_t threadSlot() {
  const int slot = tbb::this_task_arena::current_thread_index();
  return size_t(slot < 0 ? 0 : slot) % kRayCounters;
}
}  // namespace

void RayTracer::countRays(uint64_t n) const {
  rays_[threadSlot()].n.fetch_add(n, std::memory_order_relaxed);
}

uint64_t RayTracer::raysOnThisThread() const {
  return rays_[threadSlot()].n.load(std::memory_order_relaxed);
}

uint64_t RayTracer::raysTraced() const {
  uint64_t total = 0;
  for (size_t i = 0; i < rayCounters_; ++i) total += rays_[i].n.load(std::memory_order_relaxed);
  return total;
}

void RayTracer::resetRayCount() {
  for (size_t i = 0; i < rayCounters_; ++i) rays_[i].n.store(0, std::memory_order_relaxed);
}

namespace {
void setRay(RTCRay& r, const Ray& in) {
  r.org_x = in.origin.x;
  r.org_y = in.origin.y;
  r.org_z = in.origin.z;
  r.dir_x = in.dir.x;
  r.dir_y = in.dir.y;
  r.dir_z = in.dir.z;
  r.tnear = in.tnear;
  r.tfar = in.tfar;
  r.time = in.time;
  r.mask = ~0u;
  r.id = 0;
  r.flags = 0;
}

void setRayLane(RTCRay8& r, int i, const Ray& in) {
  r.org_x[i] = in.origin.x;
  r.org_y[i] = in.origin.y;
  r.org_z[i] = in.origin.z;
  r.dir_x[i] = in.dir.x;
  r.dir_y[i] = in.dir.y;
  r.dir_z[i] = in.dir.z;
  r.tnear[i] = in.tnear;
  r.tfar[i] = in.tfar;
  r.time[i] = in.time;
  r.mask[i] = ~0u;
  r.flags[i] = 0;
}

// The active lanes of `rays` as one coherent occlusion packet through `qc` (tfar < 0 where
// something blocks); returns how many lanes were active (0: nothing traced).
int occludedPacket(RTCScene scene, QueryContext& qc, const Ray* rays, const bool* active,
                   RTCRay8& r) {
  qc.ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(32) int valid[8];
  int count = 0;
  for (int i = 0; i < 8; ++i) {
    valid[i] = active[i] ? -1 : 0;
    count += active[i] ? 1 : 0;
    setRayLane(r, i, rays[active[i] ? i : 0]);
    r.id[i] = unsigned(i);
  }
  if (count > 0) rtcOccluded8(valid, scene, &qc.ctx, &r);
  return count;
}
}  // namespace

Hit RayTracer::intersect(const Ray& in, bool cullBackfaces) const {
  QueryContext qc;
  rtcInitIntersectContext(&qc.ctx);
  qc.frame = frame_;
  if (cullBackfaces) qc.ctx.filter = cullBackfaceHit;
  RTCRayHit rh;
  setRay(rh.ray, in);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &qc.ctx, &rh);
  countRays(1);
  Hit h;
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    h.object = int(rh.hit.geomID);
    h.prim = int(rh.hit.primID);
    h.t = rh.ray.tfar;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
  }
  return h;
}

bool RayTracer::occluded(const Ray& in) const {
  QueryContext qc;
  rtcInitIntersectContext(&qc.ctx);
  qc.frame = frame_;
  RTCRay r;
  setRay(r, in);
  rtcOccluded1(scene_, &qc.ctx, &r);
  countRays(1);
  return r.tfar < 0;
}

void RayTracer::occluded8(const Ray* rays, const bool* active, bool* out) const {
  QueryContext qc;
  rtcInitIntersectContext(&qc.ctx);
  qc.frame = frame_;
  alignas(32) RTCRay8 r;
  const int count = occludedPacket(scene_, qc, rays, active, r);
  if (count == 0) return;
  countRays(uint64_t(count));
  for (int i = 0; i < 8; ++i)
    if (active[i]) out[i] = r.tfar[i] < 0;
}

Vec3 RayTracer::transmittance(const Ray& in, bool textured) const {
  ShadowLane lane;
  QueryContext qc;
  rtcInitIntersectContext(&qc.ctx);
  qc.frame = frame_;
  qc.shadow = &lane;
  qc.texturedShadows = textured;
  RTCRay r;
  setRay(r, in);
  rtcOccluded1(scene_, &qc.ctx, &r);
  countRays(1);
  return r.tfar < 0 ? Vec3(0.0f) : lane.transmittance;
}

void RayTracer::transmittance8(const Ray* rays, const bool* active, Vec3* out,
                               bool textured) const {
  ShadowLane lanes[8];
  QueryContext qc;
  rtcInitIntersectContext(&qc.ctx);
  qc.frame = frame_;
  qc.shadow = lanes;
  qc.texturedShadows = textured;
  alignas(32) RTCRay8 r;
  const int count = occludedPacket(scene_, qc, rays, active, r);
  if (count == 0) return;
  countRays(uint64_t(count));
  for (int i = 0; i < 8; ++i)
    if (active[i]) out[i] = r.tfar[i] < 0 ? Vec3(0.0f) : lanes[i].transmittance;
}

void RayTracer::intersect8(const Ray* rays, int count, Hit* hits, bool cullBackfaces) const {
  QueryContext qc;
  rtcInitIntersectContext(&qc.ctx);
  qc.ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  qc.frame = frame_;
  if (cullBackfaces) qc.ctx.filter = cullBackfaceHit;
  alignas(32) int valid[8];
  alignas(32) RTCRayHit8 rh;
  for (int i = 0; i < 8; ++i) {
    valid[i] = i < count ? -1 : 0;
    setRayLane(rh.ray, i, rays[i < count ? i : 0]);
    rh.ray.id[i] = unsigned(i);
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect8(valid, scene_, &qc.ctx, &rh);
  countRays(uint64_t(count));
  for (int i = 0; i < count; ++i) {
    Hit h;
    if (rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID) {
      h.object = int(rh.hit.geomID[i]);
      h.prim = int(rh.hit.primID[i]);
      h.t = rh.ray.tfar[i];
      h.u = rh.hit.u[i];
      h.v = rh.hit.v[i];
    }
    hits[i] = h;
  }
}

}  // namespace tandem
