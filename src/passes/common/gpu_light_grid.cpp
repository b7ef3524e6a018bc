#include "passes/common/gpu_light_grid.h"

namespace tandem {

GpuLightGrid gpuLightGrid(GpuFrame& gpu, const LightGrid* grid,
                          const std::vector<int>& candidates) {
  GpuLightGrid g{};
  const std::vector<int>& picked = grid ? grid->candidates() : candidates;
  // One cell whose distribution is all zero: LightGrid::pick's uniform fallback.
  std::vector<float> cdf(std::max<size_t>(picked.size(), 1), 0.0f);
  if (grid && !grid->cdf().empty()) cdf = grid->cdf();
  std::vector<int32_t> ids(picked.begin(), picked.end());
  if (ids.empty()) ids.push_back(-1);
  g.count = int32_t(picked.size());
  for (int k = 0; k < 3; ++k) {
    g.dims[k] = grid ? grid->cells(k) : 1;
    g.lo[k] = grid ? grid->bounds().lo[k] : 0.0f;
    g.invCell[k] = grid ? grid->invCell()[k] : 0.0f;
  }
  g.cdf = gpu.constants(cdf.data(), cdf.size() * sizeof(float));
  g.candidates = gpu.constants(ids.data(), ids.size() * sizeof(int32_t));
  return g;
}

}  // namespace tandem
