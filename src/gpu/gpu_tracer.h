// Rays on the GPU outside a pipeline: the scene's BVHs on the device and the closest-hit kernel
// over a batch of rays (tests compare it with RayTracer; passes record the kernel themselves).
#pragma once
#include <memory>
#include <vector>

#include "gpu/gpu_commands.h"
#include "gpu/gpu_device.h"
#include "gpu/gpu_kernel.h"
#include "gpu/gpu_memory.h"
#include "gpu/gpu_scene.h"

namespace tandem {

class GpuTracer {
 public:
  explicit GpuTracer(std::shared_ptr<GpuDevice> device);
  ~GpuTracer();
  void update(const FrameScene& fs) { scene_.update(fs, commands_); }
  // The closest hit of every ray (both faces).
  std::vector<GpuHit> closest(const std::vector<GpuRay>& rays) { return trace(rays, closest_); }
  // Whether each ray hits anything between tnear and tfar (1) or not (0).
  std::vector<uint8_t> occluded(const std::vector<GpuRay>& rays);
  double lastKernelMs() const { return lastMs_; }  // GPU time of the last batch
  const GpuScene& scene() const { return scene_; }

 private:
  std::shared_ptr<GpuDevice> device_;
  GpuMemory memory_;
  GpuCommands commands_;
  GpuScene scene_;
  std::vector<GpuHit> trace(const std::vector<GpuRay>& rays, const GpuKernel& kernel);
  GpuKernel closest_, any_;
  GpuBuffer rays_, hits_, staging_;
  double lastMs_ = 0;
};

}  // namespace tandem
