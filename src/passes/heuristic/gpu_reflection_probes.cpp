#include "passes/heuristic/gpu_reflection_probes.h"

#include <atomic>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>

#include "gpu/gpu_camera.h"
#include "gpu/shaders/fallback_args.h"
#include "gpu/shaders/gbuffer_args.h"
#include "gpu/shaders/raster_args.h"
#include "gpu/shaders/raster_resolve_spv.h"
#include "passes/common/gpu_visible_surfaces.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "raster/rasterizer.h"

namespace tandem {

namespace {

class GpuProbeDevice final : public ProbeDevice {
 public:
  // The frame the next draw records for; true when the probes held were lost since (a pipeline
  // switch dropped the frame's scratch) and must be drawn anew.
  bool bind(FrameContext& ctx) {
    ctx_ = &ctx;
    if (generation_ == ctx.gpu->generation()) return false;
    generation_ = ctx.gpu->generation();
    faces_.clear();
    return true;
  }
  // Object o's six faces (size x size RGB floats each, one after another).
  uint64_t faces(size_t o) const {
    auto it = faces_.find(o);
    if (it == faces_.end())
      throw std::logic_error("probes: object " + std::to_string(o) + "'s was never drawn");
    return it->second;
  }

  void draw(const FrameScene& fs, int object, const Camera* cameras, int size,
            const std::vector<uint8_t>& others) override {
    GpuFrame& g = *ctx_->gpu;
    GpuCommands& cmd = g.commands();
    const Scene& scene = *fs.scene;
    size_t triangles = 0;
    for (const Object& o : scene.objects) triangles += scene.meshes[size_t(o.mesh)].triangleCount();
    const size_t pixels = size_t(size) * size_t(size), face = pixels * 3 * sizeof(float);
    const GpuBuffer& out = g.scratch(key(size_t(object)), 6 * face);
    faces_[size_t(object)] = out.address;
    const GpuBuffer& vis = g.scratch("probes:visibility", pixels * sizeof(uint64_t));
    const RasterQueue queue = rasterQueue(g, "probes:raster_queue", triangles);
    std::vector<uint32_t> draw(std::max<size_t>(others.size(), 1), 0);
    const uint64_t scene_ = g.scene(fs).sceneAddress();
    const GpuKernel& resolve = g.kernel("raster_resolve", kRasterResolveSpv,
                                        sizeof(kRasterResolveSpv) / 4, sizeof(RasterResolveArgs));
    for (int f = 0; f < 6; ++f) {
      const Camera& cam = cameras[f];
      // Objects outside the face's frustum left out on the host, as the CPU's rasterizer does.
      for (size_t o = 0; o < others.size(); ++o)
        draw[o] = others[o] && !boundsOutsideFrustum(cam.viewProj, fs.objects[o].bounds) ? 1 : 0;
      cmd.fill(vis, 0, pixels * sizeof(uint64_t), 0);
      // Texels at level 0, as resolveSurface without a spread.
      recordRasterizer(g, scene, scene_, queue,
                       RasterView{&cam, 0.0f, &draw, &vis, /*bothFaces=*/false});
      GpuView v{};
      v.camera = gpuCamera(cam, 0.0f);
      std::memcpy(v.viewProj, &cam.viewProj.m[0][0], sizeof v.viewProj);
      std::memcpy(v.prevViewProj, &cam.viewProj.m[0][0], sizeof v.prevViewProj);
      v.depthOrigin[0] = cam.desc.position.x, v.depthOrigin[1] = cam.desc.position.y;
      v.depthOrigin[2] = cam.desc.position.z;
      v.farPlane = cam.desc.farPlane;
      v.perspective = 1;
      RasterResolveArgs a{};
      a.scene = scene_;
      a.view = g.constants(&v, sizeof v);
      a.visibility = vis.address;
      a.hdr = out.address + size_t(f) * face;
      a.frameWidth = size;
      a.objectCount = uint32_t(fs.objects.size());
      a.probe = 1;
      cmd.dispatch(resolve, uint32_t(size + 7) / 8, uint32_t(size + 7) / 8, 1, &a);
      cmd.barrier();
    }
  }

  void release(int object) override {
    faces_.erase(size_t(object));
    ctx_->gpu->dropScratch(key(size_t(object)));
  }

 private:
  std::string key(size_t object) const {
    return "probes:" + std::to_string(id_) + ":" + std::to_string(object);
  }
  static uint64_t nextId() {
    static std::atomic<uint64_t> next{1};
    return next++;
  }
  const uint64_t id_ = nextId();
  FrameContext* ctx_ = nullptr;
  uint64_t generation_ = ~0ull;
  std::map<size_t, uint64_t> faces_;
};

}  // namespace

void drawProbesOnDevice(FrameContext& ctx, ReflectionProbes& probes) {
  if (!probes.device()) probes.drawOn(std::make_unique<GpuProbeDevice>());
  auto* d = dynamic_cast<GpuProbeDevice*>(probes.device());
  if (!d) throw std::logic_error("probes: drawn by another device");
  if (d->bind(ctx)) probes.invalidate();
}

uint64_t gpuProbes(FrameContext& ctx, const ReflectionProbes& probes) {
  const auto* d = dynamic_cast<const GpuProbeDevice*>(probes.device());
  if (!d) throw std::logic_error("probes: not drawn on the device");
  std::vector<GpuProbe> out(std::max<size_t>(probes.objects(), 1));
  for (size_t o = 0; o < probes.objects(); ++o) {
    const ReflectionProbes::ProbeView p = probes.probe(o);
    GpuProbe& g = out[o];
    g.size = p.size;
    if (p.size == 0) continue;
    for (int f = 0; f < 6; ++f)
      std::memcpy(g.viewProj[f], &p.cameras[f].viewProj.m[0][0], sizeof g.viewProj[f]);
    g.centre[0] = p.centre.x, g.centre[1] = p.centre.y, g.centre[2] = p.centre.z;
    g.radius = p.radius;
    g.faces = d->faces(o);
  }
  return ctx.gpu->constants(out.data(), out.size() * sizeof(GpuProbe));
}

}  // namespace tandem
