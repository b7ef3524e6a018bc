#include "gpu/gpu_tracer.h"

#include <cstring>

#include "gpu/shaders/trace_any_spv.h"
#include "gpu/shaders/trace_closest_spv.h"

namespace tandem {

GpuTracer::GpuTracer(std::shared_ptr<GpuDevice> device)
    : device_(std::move(device)),
      memory_(*device_),
      commands_(*device_),
      scene_(memory_),
      closest_(*device_, "trace_closest", kTraceClosestSpv, sizeof(kTraceClosestSpv) / 4,
               sizeof(TraceArgs)),
      any_(*device_, "trace_any", kTraceAnySpv, sizeof(kTraceAnySpv) / 4, sizeof(TraceArgs)) {}

GpuTracer::~GpuTracer() {
  memory_.release(rays_);
  memory_.release(hits_);
  memory_.release(staging_);
}

std::vector<uint8_t> GpuTracer::occluded(const std::vector<GpuRay>& rays) {
  const std::vector<GpuHit> hits = trace(rays, any_);
  std::vector<uint8_t> out(hits.size());
  for (size_t i = 0; i < hits.size(); ++i) out[i] = hits[i].object >= 0 ? 1 : 0;
  return out;
}

std::vector<GpuHit> GpuTracer::trace(const std::vector<GpuRay>& rays, const GpuKernel& kernel) {
  std::vector<GpuHit> hits(rays.size());
  if (rays.empty()) return hits;
  if (rays.size() > size_t(65535) * 64)
    throw GpuError("GPU: more than 4,194,240 rays in one batch");
  const size_t rayBytes = rays.size() * sizeof(GpuRay), hitBytes = hits.size() * sizeof(GpuHit);
  auto ensure = [&](GpuBuffer& b, size_t bytes, MemoryUse use) {
    if (b && b.size < bytes) memory_.release(b);
    if (!b) b = memory_.allocate(bytes, use);
  };
  ensure(rays_, rayBytes, MemoryUse::Device);
  ensure(hits_, hitBytes, MemoryUse::Device);
  ensure(staging_, std::max(rayBytes, hitBytes), MemoryUse::Readback);  // the hits read back
  std::memcpy(staging_.mapped, rays.data(), rayBytes);
  TraceArgs a = scene_.traceArgs();
  a.rays = rays_.address;
  a.hits = hits_.address;
  a.count = uint32_t(rays.size());
  commands_.begin();
  commands_.copy(staging_, rays_, rayBytes);
  commands_.barrier();
  const uint32_t t0 = commands_.timestamp();
  commands_.dispatch(kernel, (a.count + 63) / 64, 1, 1, &a);
  const uint32_t t1 = commands_.timestamp();
  commands_.barrier();
  commands_.copy(hits_, staging_, hitBytes);
  commands_.submit();
  lastMs_ = commands_.msBetween(t0, t1);
  std::memcpy(hits.data(), staging_.mapped, hitBytes);
  return hits;
}

}  // namespace tandem
