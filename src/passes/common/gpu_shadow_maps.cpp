#include "passes/common/gpu_shadow_maps.h"

#include <cstring>

#include "core/profiler.h"
#include "gpu/shaders/lights_in_view_spv.h"
#include "gpu/shaders/shadow_maps_data.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/gpu_gbuffer.h"

namespace tandem {

namespace {

constexpr size_t align16(size_t n) {
  return (n + 15) / 16 * 16;
}

// Where each part of the device copy lies, from its start.
struct Layout {
  size_t lights = 0, faces = 0, bytes = 0;
  std::vector<size_t> texels;  // per face: its depth, near, opaque arrays one after another
};

Layout layout(const ShadowMaps& maps, const std::vector<std::vector<ShadowMaps::FaceView>>& all) {
  Layout l;
  l.lights = align16(sizeof(GpuShadowMapsHeader));
  size_t faces = 0;
  for (const auto& f : all) faces += f.size();
  l.faces = align16(l.lights + maps.lights() * sizeof(GpuShadowLight));
  size_t at = align16(l.faces + faces * sizeof(GpuShadowFace));
  for (const auto& light : all)
    for (const ShadowMaps::FaceView& f : light) {
      l.texels.push_back(at);
      const size_t n = size_t(f.width) * size_t(f.height);
      at = align16(at + n * (2 * sizeof(float) + sizeof(ConservativeDepth::Texel)));
    }
  l.bytes = at;
  return l;
}

}  // namespace

uint64_t gpuShadowMaps(FrameContext& ctx, const ShadowMaps& maps) {
  std::vector<std::vector<ShadowMaps::FaceView>> all(maps.lights());
  for (size_t i = 0; i < all.size(); ++i) all[i] = maps.faceViews(i);
  const Layout l = layout(maps, all);
  const auto t0 = Clock::now();
  size_t moved = 0;
  const uint64_t address = ctx.gpu->residentScratch(
      "shadow_maps:" + std::to_string(uintptr_t(&maps)), maps.version(), l.bytes,
      [&](void* image, uint64_t base) {
        auto* bytes = static_cast<char*>(image);
        GpuShadowMapsHeader h{};
        h.lights = base + l.lights;
        h.faces = base + l.faces;
        h.lightCount = uint32_t(all.size());
        std::memcpy(bytes, &h, sizeof h);
        size_t face = 0;
        for (size_t i = 0; i < all.size(); ++i) {
          const GpuShadowLight gl{int32_t(face), int32_t(all[i].size()),
                                  maps.castsShadows(i) ? 1 : 0, 0};
          std::memcpy(bytes + l.lights + i * sizeof gl, &gl, sizeof gl);
          for (const ShadowMaps::FaceView& f : all[i]) {
            const Camera& c = *f.camera;
            GpuShadowFace g{};
            for (int r = 0; r < 4; ++r)
              for (int k = 0; k < 4; ++k) g.viewProj[4 * r + k] = c.viewProj.m[r][k];
            g.eye[0] = c.desc.position.x, g.eye[1] = c.desc.position.y,
            g.eye[2] = c.desc.position.z;
            g.forward[0] = c.forward.x, g.forward[1] = c.forward.y, g.forward[2] = c.forward.z;
            g.texelPerDistance = f.texelPerDistance;
            g.nearPlane = c.desc.nearPlane;
            g.farPlane = c.desc.farPlane;
            g.width = f.width;
            g.height = f.height;
            g.perspective = c.desc.projection == Projection::Perspective ? 1 : 0;
            const size_t n = size_t(f.width) * size_t(f.height), at = l.texels[face];
            g.depth = base + at;
            g.near = base + at + n * sizeof(float);
            g.opaque = g.near + n * sizeof(ConservativeDepth::Texel);
            std::memcpy(bytes + l.faces + face * sizeof g, &g, sizeof g);
            std::memcpy(bytes + at, f.depth, n * sizeof(float));
            std::memcpy(bytes + (g.near - base), f.near, n * sizeof(ConservativeDepth::Texel));
            std::memcpy(bytes + (g.opaque - base), f.opaqueDepth, n * sizeof(float));
            ++face;
          }
        }
      },
      &moved);
  if (moved) ctx.passParts.push_back({"shadow_maps_upload", msSince(t0), 0, double(moved)});
  return address;
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
