#include "passes/common/gpu_shadow_maps.h"

#include <atomic>
#include <cstring>
#include <map>
#include <stdexcept>

#include "core/profiler.h"
#include "gpu/gpu_camera.h"
#include "gpu/shaders/conservative_depth_spv.h"
#include "gpu/shaders/lights_in_view_spv.h"
#include "gpu/shaders/raster_args.h"
#include "gpu/shaders/shadow_map_draw_args.h"
#include "gpu/shaders/shadow_map_texels_spv.h"
#include "gpu/shaders/shadow_maps_data.h"
#include "passes/common/gpu_visible_surfaces.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/gpu_gbuffer.h"
#include "pipeline/pass.h"
#include "raster/rasterizer.h"

namespace tandem {

namespace {

constexpr size_t kQueueHeader = 16;  // a queue's count, padded
// Workgroups that share out the queued bands (each band a few hundred loop iterations: lavapipe
// ends a loop after 65535, counted over a workgroup's run).
constexpr uint32_t kConservativeQueueGroups = 1024;

uint32_t groupsOf(size_t n, uint32_t size) {
  return uint32_t((n + size - 1) / size);
}

// The maps of one ShadowMaps, drawn and kept on the device (scratch buffers of the GpuFrame).
class GpuShadowMapDevice final : public ShadowMapDevice {
 public:
  struct Face {
    int width = 0, height = 0;
    const GpuBuffer *depth = nullptr, *near = nullptr, *opaque = nullptr;
    const GpuBuffer *staticDepth = nullptr, *staticNear = nullptr;
  };

  // The frame and pass the next draw records for; the maps held are gone when the frame's
  // scratch was dropped since (a pipeline switch): true then, and the caller redraws them all.
  bool bind(FrameContext& ctx, const Pass& pass) {
    ctx_ = &ctx;
    pass_ = &pass;
    if (generation_ == ctx.gpu->generation()) return false;
    generation_ = ctx.gpu->generation();
    faces_.clear();
    return true;
  }
  GpuFrame& gpu() const { return *ctx_->gpu; }
  const Face& face(size_t light, size_t face) const {
    auto it = faces_.find({light, face});
    if (it == faces_.end())
      throw std::logic_error("shadow maps: face " + std::to_string(face) + " of light " +
                             std::to_string(light) + " was never drawn on the device");
    return it->second;
  }

  void draw(const FrameScene& fs, const std::vector<Job>& jobs, bool keepStatic, bool sweep,
            const std::vector<uint8_t>& opaqueCasters,
            const std::vector<uint8_t>& solidCasters) override;

 private:
  Face& makeFace(const Job& job, bool keepStatic);
  void drawCasters(const FrameScene& fs, const Job& job, const Face& f, bool sweep,
                   const std::vector<uint8_t>& solid);
  void texels(const Job& job, const Face& f, uint32_t mode, uint64_t opaqueCasters);

  static uint64_t nextId() {
    static std::atomic<uint64_t> next{1};
    return next++;
  }
  const uint64_t id_ = nextId();
  FrameContext* ctx_ = nullptr;
  const Pass* pass_ = nullptr;
  uint64_t generation_ = ~0ull;
  std::map<std::pair<size_t, size_t>, Face> faces_;
  uint64_t scene_ = 0;
  size_t triangles_ = 0;
};

GpuShadowMapDevice::Face& GpuShadowMapDevice::makeFace(const Job& job, bool keepStatic) {
  const int w = job.camera.width, h = job.camera.height;
  const size_t n = size_t(w) * size_t(h);
  const std::string key = "shadow_maps:" + std::to_string(id_) + ":" + std::to_string(job.light) +
                          ":" + std::to_string(job.face) + ":";
  GpuFrame& g = gpu();
  Face& f = faces_[{job.light, job.face}];
  f.width = w;
  f.height = h;
  f.depth = &g.scratch(key + "depth", n * sizeof(uint64_t));
  f.near = &g.scratch(key + "near", n * sizeof(uint64_t));
  f.opaque = &g.scratch(key + "opaque", n * sizeof(float));
  f.staticDepth = keepStatic ? &g.scratch(key + "static_depth", n * sizeof(uint64_t)) : nullptr;
  f.staticNear = keepStatic ? &g.scratch(key + "static_near", n * sizeof(uint64_t)) : nullptr;
  return f;
}

void GpuShadowMapDevice::texels(const Job& job, const Face& f, uint32_t mode,
                                uint64_t opaqueCasters) {
  GpuFrame& g = gpu();
  ShadowTexelArgs a{};
  a.scene = scene_;
  a.depth = f.depth->address;
  a.near = f.near->address;
  a.staticDepth = f.staticDepth ? f.staticDepth->address : 0;
  a.staticNear = f.staticNear ? f.staticNear->address : 0;
  a.opaque = f.opaque->address;
  a.opaqueCasters = opaqueCasters;
  a.width = f.width;
  a.x0 = job.x0, a.y0 = job.y0, a.x1 = job.x1, a.y1 = job.y1;
  a.mode = mode;
  a.objectCount = uint32_t(ctx_->frame.objects.size());
  const uint64_t args = g.constants(&a, sizeof a);
  const GpuKernel& k = g.kernel("shadow_map_texels", kShadowMapTexelsSpv,
                                sizeof(kShadowMapTexelsSpv) / 4, sizeof(uint64_t));
  g.commands().dispatch(k, groupsOf(size_t(job.x1 - job.x0), 8),
                        groupsOf(size_t(job.y1 - job.y0), 8), 1, &args);
  g.commands().barrier();
}

void GpuShadowMapDevice::drawCasters(const FrameScene& fs, const Job& job, const Face& f,
                                     bool sweep, const std::vector<uint8_t>& solid) {
  GpuFrame& g = gpu();
  GpuCommands& cmd = g.commands();
  const Camera& cam = job.camera;
  const size_t objects = fs.objects.size();
  // The depth map: the solid casters' triangles, both faces, through the compute rasterizer
  // (objects outside the face's frustum left out on the host, as the CPU's rasterizer leaves
  // them).
  std::vector<uint32_t> draw(std::max<size_t>(objects, 1), 0);
  for (size_t o = 0; o < objects; ++o)
    draw[o] = job.casters[o] && o < solid.size() && solid[o] &&
                      !boundsOutsideFrustum(cam.viewProj, fs.objects[o].bounds)
                  ? 1
                  : 0;
  const RasterQueue queue = rasterQueue(g, "shadow_maps:raster_queue", triangles_);
  recordRasterizer(g, *fs.scene, scene_, queue,
                   RasterView{&cam, 0.0f, &draw, f.depth, /*bothFaces=*/true});

  // The conservative map: the same casters, those moving over an open shutter as their box.
  // Objects beyond the far plane stay (a perspective map stores them at a depth near 0, as the
  // CPU does); the other planes leave out what could touch no texel.
  constexpr unsigned kAllButFar = 0x3f & ~2u;
  std::vector<ConservativeWorldTriangle> boxes;
  for (size_t o = 0; o < objects; ++o) {
    draw[o] =
        job.casters[o] && !boundsOutsideFrustum(cam.viewProj, fs.objects[o].bounds, kAllButFar) ? 1
                                                                                                : 0;
    if (!draw[o] || !sweep || fs.objects[o].stepPositions.empty()) continue;
    draw[o] = 0;
    for (const auto& t : boxTriangles(fs.objects[o].bounds)) {
      ConservativeWorldTriangle w{};
      const Vec3* v[3] = {&t[0], &t[1], &t[2]};
      float* out[3] = {w.a, w.b, w.c};
      for (int k = 0; k < 3; ++k) out[k][0] = v[k]->x, out[k][1] = v[k]->y, out[k][2] = v[k]->z;
      w.object = uint32_t(o);
      boxes.push_back(w);
    }
  }
  const size_t capacity = std::min<size_t>(std::max<size_t>(triangles_, 1024), size_t(1) << 18);
  const GpuBuffer& cq = g.scratch("shadow_maps:conservative_queue",
                                  kQueueHeader + capacity * sizeof(ConservativeTriangle));
  const RasterSpans meshes = rasterSpans(g, *fs.scene, draw);
  ConservativeArgs c{};
  c.scene = scene_;
  c.spans = meshes.address;
  c.spanCount = meshes.count;
  c.boxes = boxes.empty() ? 0 : g.constants(boxes.data(), boxes.size() * sizeof(boxes[0]));
  c.near = f.near->address;
  c.queue = cq.address;
  std::memcpy(c.viewProj, &cam.viewProj.m[0][0], sizeof c.viewProj);
  const Vec3 eye = cam.desc.position, fwd = cam.forward;
  c.eye[0] = eye.x, c.eye[1] = eye.y, c.eye[2] = eye.z;
  c.forward[0] = fwd.x, c.forward[1] = fwd.y, c.forward[2] = fwd.z;
  c.nearPlane = cam.desc.nearPlane;
  c.farPlane = cam.desc.farPlane;
  c.width = cam.width;
  c.height = cam.height;
  c.perspective = cam.desc.projection == Projection::Perspective ? 1 : 0;
  c.triangles = uint32_t(meshes.triangles);
  c.objectCount = uint32_t(objects);
  c.boxTriangles = uint32_t(boxes.size());
  c.queueCapacity = uint32_t(capacity);
  c.phase = TD_CONSERVATIVE_SETUP;
  const uint64_t setup = g.constants(&c, sizeof c);
  c.phase = TD_CONSERVATIVE_QUEUE;
  const uint64_t large = g.constants(&c, sizeof c);
  const GpuKernel& k = g.kernel("conservative_depth", kConservativeDepthSpv,
                                sizeof(kConservativeDepthSpv) / 4, sizeof(uint64_t));
  cmd.fill(cq, 0, kQueueHeader, 0);
  cmd.barrier();
  const uint32_t groups = groupsOf(meshes.triangles + boxes.size(), 64);
  if (groups > 0) {
    const uint32_t gx = std::min<uint32_t>(groups, 4096);
    cmd.dispatch(k, gx, (groups + gx - 1) / gx, 1, &setup);
    cmd.barrier();
    cmd.dispatch(k, kConservativeQueueGroups, 1, 1, &large);
    cmd.barrier();
  }
}

void GpuShadowMapDevice::draw(const FrameScene& fs, const std::vector<Job>& jobs, bool keepStatic,
                              bool sweep, const std::vector<uint8_t>& opaqueCasters,
                              const std::vector<uint8_t>& solidCasters) {
  if (jobs.empty()) return;
  GpuFrame& g = gpu();
  GpuCommands& cmd = g.commands();
  scene_ = g.scene(fs).sceneAddress();
  const Scene& scene = *fs.scene;
  triangles_ = 0;
  for (const Object& o : scene.objects) triangles_ += scene.meshes[size_t(o.mesh)].triangleCount();
  std::vector<uint32_t> opaque(std::max<size_t>(opaqueCasters.size(), 1), 0);
  for (size_t o = 0; o < opaqueCasters.size(); ++o) opaque[o] = opaqueCasters[o];
  const uint64_t opaqueAddress = g.constants(opaque.data(), opaque.size() * sizeof(uint32_t));
  const uint32_t t0 = cmd.timestamp();
  for (const Job& job : jobs) {
    if (job.x1 <= job.x0 || job.y1 <= job.y0) continue;
    const Face* f = nullptr;
    if (job.fresh) {
      f = &makeFace(job, keepStatic);
      const size_t n = size_t(f->width) * size_t(f->height);
      cmd.fill(*f->depth, 0, n * sizeof(uint64_t), 0);
      cmd.fill(*f->near, 0, n * sizeof(uint64_t), 0);
      cmd.barrier();
    } else {
      f = &face(job.light, job.face);
      if (!f->staticDepth)
        throw std::logic_error("shadow maps: moving casters drawn without a static copy");
      texels(job, *f, TD_TEXELS_RESTORE, opaqueAddress);
    }
    if (!job.casters.empty()) drawCasters(fs, job, *f, sweep, solidCasters);
    if (job.fresh && f->staticDepth) {
      const size_t bytes = size_t(f->width) * size_t(f->height) * sizeof(uint64_t);
      cmd.copy(*f->depth, *f->staticDepth, bytes);
      cmd.copy(*f->near, *f->staticNear, bytes);
      cmd.barrier();
    }
    texels(job, *f, TD_TEXELS_OPAQUE, opaqueAddress);
  }
  const uint32_t t1 = cmd.timestamp();
  FrameContext& ctx = *ctx_;
  g.afterSubmit([&ctx, &cmd, t0, t1] {
    ctx.passParts.push_back({"shadow_maps", cmd.activeMs(t0, t1), 0});
  });
}

GpuShadowMapDevice* deviceOf(const ShadowMaps& maps) {
  auto* d = dynamic_cast<GpuShadowMapDevice*>(maps.device());
  if (!d) throw std::logic_error("shadow maps: not drawn on the device");
  return d;
}

}  // namespace

const ShadowMaps& deviceShadowMaps(FrameContext& ctx, const Pass& pass, int resolution,
                                   const std::vector<uint8_t>* wanted) {
  ShadowMaps& maps = ctx.deviceShadowMaps(resolution);
  if (!maps.device()) maps.drawOn(std::make_unique<GpuShadowMapDevice>());
  if (deviceOf(maps)->bind(ctx, pass)) maps.invalidate();
  maps.update(ctx.frame, resolution, wanted);
  return maps;
}

uint64_t gpuShadowMaps(FrameContext& ctx, const ShadowMaps& maps) {
  const GpuShadowMapDevice& device = *deviceOf(maps);
  GpuFrame& gpu = *ctx.gpu;
  std::vector<GpuShadowLight> lights;
  std::vector<GpuShadowFace> faces;
  for (size_t i = 0; i < maps.lights(); ++i) {
    const std::vector<ShadowMaps::FaceView> views = maps.faceViews(i);
    lights.push_back(
        {int32_t(faces.size()), int32_t(views.size()), maps.castsShadows(i) ? 1 : 0, 0});
    for (size_t k = 0; k < views.size(); ++k) {
      const ShadowMaps::FaceView& v = views[k];
      const GpuShadowMapDevice::Face& held = device.face(i, k);
      const Camera& c = *v.camera;
      GpuShadowFace g{};
      std::memcpy(g.viewProj, &c.viewProj.m[0][0], sizeof g.viewProj);
      g.eye[0] = c.desc.position.x, g.eye[1] = c.desc.position.y, g.eye[2] = c.desc.position.z;
      g.forward[0] = c.forward.x, g.forward[1] = c.forward.y, g.forward[2] = c.forward.z;
      g.texelPerDistance = v.texelPerDistance;
      g.nearPlane = c.desc.nearPlane;
      g.farPlane = c.desc.farPlane;
      g.width = v.width;
      g.height = v.height;
      g.perspective = c.desc.projection == Projection::Perspective ? 1 : 0;
      g.depth = held.depth->address;
      g.near = held.near->address;
      g.opaque = held.opaque->address;
      faces.push_back(g);
    }
  }
  GpuShadowMapsHeader h{};
  if (!lights.empty()) h.lights = gpu.constants(lights.data(), lights.size() * sizeof(lights[0]));
  if (!faces.empty()) h.faces = gpu.constants(faces.data(), faces.size() * sizeof(faces[0]));
  h.lightCount = uint32_t(lights.size());
  return gpu.constants(&h, sizeof h);
}

DeviceShadowFace readDeviceShadowFace(const ShadowMaps& maps, size_t light, size_t face) {
  const GpuShadowMapDevice& device = *deviceOf(maps);
  const GpuShadowMapDevice::Face& f = device.face(light, face);
  const size_t n = size_t(f.width) * size_t(f.height);
  DeviceShadowFace out;
  out.width = f.width;
  out.height = f.height;
  std::vector<uint64_t> keys(n);
  device.gpu().readBack(*f.depth, n * sizeof(uint64_t), keys.data());
  out.depth.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const uint32_t bits = uint32_t(keys[k] >> 32);
    std::memcpy(&out.depth[k], &bits, sizeof bits);
  }
  device.gpu().readBack(*f.near, n * sizeof(uint64_t), keys.data());
  out.near.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const uint32_t bits = uint32_t(keys[k] >> 32);
    std::memcpy(&out.near[k].depth, &bits, sizeof bits);
    out.near[k].object = ~uint32_t(keys[k]);
  }
  out.opaque.resize(n);
  device.gpu().readBack(*f.opaque, n * sizeof(float), out.opaque.data());
  return out;
}

const uint32_t* recordLightsInView(FrameContext& ctx, const Pass& pass) {
  GpuFrame& gpu = *ctx.gpu;
  struct Push {  // lights_in_view.comp's push constants
    uint64_t scene, sources, flags;
    int32_t viewX, viewY, viewWidth, viewHeight, frameWidth, pad;
  } a{};
  const std::vector<uint32_t> zero(std::max<size_t>(ctx.scene->lights.size(), 1), 0);
  a.scene = gpu.scene(ctx.frame).sceneAddress();
  a.sources = gbufferDeviceSources(ctx, pass);
  a.flags = gpu.constants(zero.data(), zero.size() * sizeof(uint32_t));
  a.frameWidth = ctx.width;
  const GpuKernel& k =
      gpu.kernel("lights_in_view", kLightsInViewSpv, sizeof(kLightsInViewSpv) / 4, sizeof(Push));
  for (const View& v : ctx.views) {
    a.viewX = v.x, a.viewY = v.y, a.viewWidth = v.width(), a.viewHeight = v.height();
    gpu.commands().dispatch(k, uint32_t(v.width() + 7) / 8, uint32_t(v.height() + 7) / 8, 1, &a);
  }
  return static_cast<const uint32_t*>(gpu.constantsData(a.flags));
}

std::vector<uint8_t> wantedLights(const uint32_t* flags, size_t lights) {
  std::vector<uint8_t> wanted(lights, 0);
  for (size_t i = 0; i < lights; ++i) wanted[i] = flags[i] != 0 ? 1 : 0;
  return wanted;
}

}  // namespace tandem
