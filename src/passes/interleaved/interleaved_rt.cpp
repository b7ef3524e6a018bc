#include "passes/interleaved/interleaved_rt.h"

#include "core/parallel.h"
#include "pipeline/frame_context.h"

namespace tandem {

void InterleavedRTPass::visibility(FrameContext& ctx, const SampleLayout& layout,
                                   const std::vector<Camera>& cams, const std::vector<float>& taus,
                                   const uint8_t* active, VisibilityBuffer& vis) {
  RayTracer& rt = ctx.rayTracer();
  for (size_t j = 0; j < cams.size(); ++j) {
    const uint32_t b = layout.passBegin(int(j)), e = layout.passEnd(int(j));
    const Camera& cam = cams[j];
    const float tau = taus[j];
    parallelBlocks(size_t(e - b), 256, [&](size_t s0, size_t s1) {
      Ray rays[8];
      Hit hits[8];
      uint32_t at[8];
      int m = 0;
      auto flush = [&] {
        rt.intersect8(rays, m, hits, /*cullBackfaces=*/true);
        for (int q = 0; q < m; ++q) {
          vis.object[at[q]] = hits[q].valid() ? uint32_t(hits[q].object) : kNoObject;
          vis.prim[at[q]] = hits[q].valid() ? uint32_t(hits[q].prim) : 0u;
        }
        m = 0;
      };
      for (size_t q = b + s0; q < b + s1; ++q) {
        const uint32_t id = layout.ids[q];
        if (active && !active[id]) continue;
        Ray& r = rays[m];
        cam.generateRay(layout.pos[id].x, layout.pos[id].y, r.origin, r.dir);
        r.time = tau;
        at[m++] = id;
        if (m == 8) flush();
      }
      if (m > 0) flush();
    });
  }
}

}  // namespace tandem
