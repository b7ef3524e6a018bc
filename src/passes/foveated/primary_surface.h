// The primary surface of a pixel as the foveated path tracer and direct_light read it from the
// G-buffer: the slots both declare, the surface sample, the sky test and the direction to the
// viewer.
#pragma once
#include <vector>

#include "pipeline/frame_context.h"
#include "pipeline/pass.h"
#include "shading/gbuffer_layout.h"
#include "shading/surface.h"

namespace tandem {

struct PrimarySurfaces {
  const Buffer &position, &normal, &geoNormal, &diffuse, &emission, &depth;

  // The G-buffer targets read, in the members' order.
  static constexpr const char* kSlots[6] = {"position", "normal",   "geo_normal",
                                            "diffuse",  "emission", "depth"};
  static std::vector<BufferSlot> slots() {
    std::vector<BufferSlot> s;
    for (const char* n : kSlots) s.push_back(gbufferSlot(n));
    return s;
  }
  static PrimarySurfaces of(const FrameContext& ctx, const Pass& pass) {
    return {ctx.input(pass, kSlots[0]), ctx.input(pass, kSlots[1]), ctx.input(pass, kSlots[2]),
            ctx.input(pass, kSlots[3]), ctx.input(pass, kSlots[4]), ctx.input(pass, kSlots[5])};
  }
  bool sky(int x, int y) const { return depth.at(x, y)[0] <= 0.0f; }
  SurfaceSample at(int x, int y) const {
    SurfaceSample s;
    s.position = position.rgb(x, y);
    s.normal = normal.rgb(x, y);
    s.geoNormal = geoNormal.rgb(x, y);
    const float* a = diffuse.at(x, y) + DiffuseChannels::kRgb;
    s.diffuse = Vec3(a[0], a[1], a[2]);
    s.emission = emission.rgb(x, y);
    return s;
  }
  // Unit direction from surface point p to view v's eye (its axis for an orthographic camera).
  static Vec3 towardsViewer(const View& v, Vec3 p) {
    return v.camera.desc.projection == Projection::Perspective
               ? normalize(v.camera.desc.position - p)
               : -v.camera.forward;
  }
};

}  // namespace tandem
