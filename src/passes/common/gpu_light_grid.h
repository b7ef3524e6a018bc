// The light selection diffuse_gi.glsl reads (shaders/light_grid_data.h), in this batch's
// constants: a LightGrid's cells, or, with none, a uniform choice among `candidates` (DiffuseGI's
// without a grid: any sampled light alike).
#pragma once
#include <vector>

#include "gpu/shaders/light_grid_data.h"
#include "pipeline/gpu_frame.h"
#include "rt/light_grid.h"

namespace tandem {

GpuLightGrid gpuLightGrid(GpuFrame& gpu, const LightGrid* grid, const std::vector<int>& candidates);

}  // namespace tandem
