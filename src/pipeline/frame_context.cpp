#include "pipeline/frame_context.h"

namespace tandem {

RayTracer& FrameContext::rayTracer() {
  if (!rt_) rt_ = std::make_unique<RayTracer>();
  rt_->update(frame);
  return *rt_;
}

Buffer& FrameContext::output(const std::string& name, int channels) {
  Buffer& b = buffers[name];
  if (b.width != width || b.height != height || b.channels != channels)
    b = Buffer(width, height, channels);
  return b;
}

const Buffer& FrameContext::input(const std::string& name) const {
  auto it = buffers.find(name);
  TANDEM_ASSERT(it != buffers.end());  // wiring was checked when the pipeline loaded
  return it->second;
}

}  // namespace tandem
