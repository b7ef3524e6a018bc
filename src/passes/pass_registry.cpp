// The explicit list of pass types (above the passes, below the built-in pipelines): one line a
// pass, its type taken from the class itself, grouped by the technique folder it lives in. Add a
// new pass here (and to src/CMakeLists.txt).
#include "passes/pass_registry.h"
#include "passes/baselines/accumulation.h"
#include "passes/baselines/pt_reference.h"
#include "passes/baselines/rt_whitted.h"
#include "passes/baselines/taa.h"
#include "passes/common/deferred_shading.h"
#include "passes/common/downsample.h"
#include "passes/common/raster_gbuffer.h"
#include "passes/common/rt_gbuffer.h"
#include "passes/common/tonemap.h"
#include "passes/common/vbuffer_shading.h"
#include "passes/dof/dof_accumulation.h"
#include "passes/dof/dof_coc.h"
#include "passes/dof/dof_composite.h"
#include "passes/dof/dof_reconstruction.h"
#include "passes/dof/postfx_dof.h"
#include "passes/dof/ray_mask.h"
#include "passes/dof/rt_dof.h"
#include "passes/foveated/direct_light.h"
#include "passes/foveated/foveated_pt.h"
#include "passes/foveated/foveation.h"
#include "passes/foveated/nh_denoise.h"
#include "passes/foveated/periphery_accumulation.h"
#include "passes/heuristic/blend.h"
#include "passes/heuristic/heuristic.h"
#include "passes/heuristic/rt_secondary.h"
#include "passes/heuristic/ss_fallback.h"
#include "passes/interleaved/interleaved_raster.h"
#include "passes/interleaved/interleaved_rt.h"
#include "passes/interleaved/mb_composite.h"
#include "passes/interleaved/postfx_motion_blur.h"
#include "pipeline/pipeline.h"

namespace tandem {

namespace {

template <class P>
PassEntry entry(const char* technique) {
  return {P().type(), technique, [] { return std::unique_ptr<Pass>(std::make_unique<P>()); }};
}

}  // namespace

const std::vector<PassEntry>& passRegistry() {
  static const std::vector<PassEntry> passes = {entry<RasterGBufferPass>("common"),
                                                entry<VBufferShadingPass>("common"),
                                                entry<RTGBufferPass>("common"),
                                                entry<DeferredShadingPass>("common"),
                                                entry<HeuristicPass>("heuristic"),
                                                entry<RTSecondaryPass>("heuristic"),
                                                entry<ScreenSpaceFallbackPass>("heuristic"),
                                                entry<BlendPass>("heuristic"),
                                                entry<RTWhittedPass>("baselines"),
                                                entry<PTReferencePass>("baselines"),
                                                entry<TAAPass>("baselines"),
                                                entry<AccumulationPass>("baselines"),
                                                entry<DownsamplePass>("common"),
                                                entry<DofCocPass>("dof"),
                                                entry<PostfxDofPass>("dof"),
                                                entry<RayMaskPass>("dof"),
                                                entry<RTDofPass>("dof"),
                                                entry<DofAccumulationPass>("dof"),
                                                entry<DofReconstructionPass>("dof"),
                                                entry<DofCompositePass>("dof"),
                                                entry<FoveationPass>("foveated"),
                                                entry<FoveatedPTPass>("foveated"),
                                                entry<DirectLightPass>("foveated"),
                                                entry<NHDenoisePass>("foveated"),
                                                entry<PeripheryAccumulationPass>("foveated"),
                                                entry<InterleavedRasterPass>("interleaved"),
                                                entry<InterleavedRTPass>("interleaved"),
                                                entry<PostfxMotionBlurPass>("interleaved"),
                                                entry<MotionBlurCompositePass>("interleaved"),
                                                entry<TonemapPass>("common")};
  return passes;
}

const std::vector<std::string>& passTypes() {
  static const std::vector<std::string> types = [] {
    std::vector<std::string> t;
    for (const PassEntry& e : passRegistry()) t.push_back(e.type);
    return t;
  }();
  return types;
}

std::unique_ptr<Pass> createPass(const std::string& type) {
  for (const PassEntry& e : passRegistry())
    if (e.type == type) return e.make();
  return nullptr;
}

}  // namespace tandem
