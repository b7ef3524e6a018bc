// The explicit list of pass types (above the passes, below the built-in pipelines). Add a new
// pass here (and to src/CMakeLists.txt).
#include "passes/baselines/accumulation.h"
#include "passes/heuristic/blend.h"
#include "passes/common/deferred_shading.h"
#include "passes/dof/dof_accumulation.h"
#include "passes/dof/dof_coc.h"
#include "passes/dof/dof_composite.h"
#include "passes/dof/dof_reconstruction.h"
#include "passes/common/downsample.h"
#include "passes/foveated/foveated_pt.h"
#include "passes/foveated/foveation.h"
#include "passes/heuristic/heuristic.h"
#include "passes/interleaved/interleaved_raster.h"
#include "passes/interleaved/interleaved_rt.h"
#include "passes/foveated/nh_denoise.h"
#include "passes/foveated/periphery_accumulation.h"
#include "passes/dof/postfx_dof.h"
#include "passes/interleaved/postfx_motion_blur.h"
#include "passes/baselines/pt_reference.h"
#include "passes/common/raster_gbuffer.h"
#include "passes/dof/ray_mask.h"
#include "passes/dof/rt_dof.h"
#include "passes/common/rt_gbuffer.h"
#include "passes/heuristic/rt_secondary.h"
#include "passes/baselines/rt_whitted.h"
#include "passes/heuristic/ss_fallback.h"
#include "passes/baselines/taa.h"
#include "passes/common/tonemap.h"
#include "passes/common/vbuffer_shading.h"
#include "pipeline/pipeline.h"

namespace tandem {

const std::vector<std::string>& passTypes() {
  static const std::vector<std::string> types = {"raster_gbuffer",
                                                 "vbuffer_shading",
                                                 "rt_gbuffer",
                                                 "deferred_shading",
                                                 "heuristic",
                                                 "rt_secondary",
                                                 "ss_fallback",
                                                 "blend",
                                                 "rt_whitted",
                                                 "pt_reference",
                                                 "taa",
                                                 "accumulation",
                                                 "downsample",
                                                 "dof_coc",
                                                 "postfx_dof",
                                                 "ray_mask",
                                                 "rt_dof",
                                                 "dof_accumulation",
                                                 "dof_reconstruction",
                                                 "dof_composite",
                                                 "foveation",
                                                 "foveated_pt",
                                                 "nh_denoise",
                                                 "periphery_accumulation",
                                                 "interleaved_raster",
                                                 "interleaved_rt",
                                                 "postfx_motion_blur",
                                                 "mb_composite",
                                                 "tonemap"};
  return types;
}

std::unique_ptr<Pass> createPass(const std::string& type) {
  if (type == "raster_gbuffer") return std::make_unique<RasterGBufferPass>();
  if (type == "vbuffer_shading") return std::make_unique<VBufferShadingPass>();
  if (type == "rt_gbuffer") return std::make_unique<RTGBufferPass>();
  if (type == "deferred_shading") return std::make_unique<DeferredShadingPass>();
  if (type == "heuristic") return std::make_unique<HeuristicPass>();
  if (type == "rt_secondary") return std::make_unique<RTSecondaryPass>();
  if (type == "ss_fallback") return std::make_unique<ScreenSpaceFallbackPass>();
  if (type == "blend") return std::make_unique<BlendPass>();
  if (type == "rt_whitted") return std::make_unique<RTWhittedPass>();
  if (type == "pt_reference") return std::make_unique<PTReferencePass>();
  if (type == "taa") return std::make_unique<TAAPass>();
  if (type == "accumulation") return std::make_unique<AccumulationPass>();
  if (type == "downsample") return std::make_unique<DownsamplePass>();
  if (type == "dof_coc") return std::make_unique<DofCocPass>();
  if (type == "postfx_dof") return std::make_unique<PostfxDofPass>();
  if (type == "ray_mask") return std::make_unique<RayMaskPass>();
  if (type == "rt_dof") return std::make_unique<RTDofPass>();
  if (type == "dof_accumulation") return std::make_unique<DofAccumulationPass>();
  if (type == "dof_reconstruction") return std::make_unique<DofReconstructionPass>();
  if (type == "dof_composite") return std::make_unique<DofCompositePass>();
  if (type == "foveation") return std::make_unique<FoveationPass>();
  if (type == "foveated_pt") return std::make_unique<FoveatedPTPass>();
  if (type == "nh_denoise") return std::make_unique<NHDenoisePass>();
  if (type == "periphery_accumulation") return std::make_unique<PeripheryAccumulationPass>();
  if (type == "interleaved_raster") return std::make_unique<InterleavedRasterPass>();
  if (type == "interleaved_rt") return std::make_unique<InterleavedRTPass>();
  if (type == "postfx_motion_blur") return std::make_unique<PostfxMotionBlurPass>();
  if (type == "mb_composite") return std::make_unique<MotionBlurCompositePass>();
  if (type == "tonemap") return std::make_unique<TonemapPass>();
  return nullptr;
}

}  // namespace tandem
