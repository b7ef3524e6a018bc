#include "pipeline/frame_context.h"

#include "shading/surface_resolve.h"

#include "pipeline/pass.h"

namespace tandem {

bool FrameContext::anyCameraMoved() const {
  for (const View& v : views)
    if (v.cameraMoved) return true;
  return false;
}

RayTracer& FrameContext::rayTracer() {
  if (!rt_) rt_ = std::make_unique<RayTracer>();
  rt_->update(frame);
  return *rt_;
}

ShadowMaps& FrameContext::shadowMaps(int resolution) {
  std::unique_ptr<ShadowMaps>& m = shadowMaps_[resolution];
  if (!m) m = std::make_unique<ShadowMaps>();
  m->update(frame, resolution);
  return *m;
}

Buffer& FrameContext::output(const Pass& pass, const std::string& slot, int w, int h) {
  const std::optional<BufferSlot> s = pass.outputSlot(slot);
  TANDEM_ASSERT(s.has_value());  // a pass writes only the slots it declares
  if (s->extent.scale != Extent::Scale::Any) s->extent.resolve(width, height, w, h);
  Buffer& b = buffers[pass.bufferName(slot)];
  if (b.width != w || b.height != h || b.channels != s->channels) b = Buffer(w, h, s->channels);
  b.kind = s->kind;
  return b;
}

double FrameContext::counter(const std::string& name, double fallback) const {
  auto it = counters.find(name);
  return it == counters.end() ? fallback : it->second;
}

double FrameContext::counter(const std::string& name) const {
  auto it = counters.find(name);
  TANDEM_ASSERT(it != counters.end());  // the pass that reports it did not run
  return it->second;
}

bool FrameContext::isConsumed(const Pass& pass, const std::string& slot) const {
  const std::string& name = pass.bufferName(slot);
  return keepAllOutputs || consumed.count(name) || wanted.count(name);
}

Buffer* FrameContext::outputIfConsumed(const Pass& pass, const std::string& slot) {
  if (isConsumed(pass, slot)) return &output(pass, slot);
  buffers.erase(pass.bufferName(slot));
  return nullptr;
}

const Buffer& FrameContext::input(const Pass& pass, const std::string& slot) const {
  return input(pass.bufferName(slot));
}

const Buffer* FrameContext::previous(const Pass& pass, const std::string& slot) const {
  auto it = history.find(pass.bufferName(slot));
  return it == history.end() ? nullptr : &it->second;
}

const Buffer* FrameContext::optionalInput(const Pass& pass, const std::string& slot) const {
  auto it = buffers.find(pass.bufferName(slot));
  return it == buffers.end() ? nullptr : &it->second;
}

const Buffer& FrameContext::input(const std::string& name) const {
  auto it = buffers.find(name);
  TANDEM_ASSERT(it != buffers.end());  // wiring was checked when the pipeline loaded
  return it->second;
}

float FrameContext::pixelSpread(const View& view) const {
  return pixelSpreadAngle(view.camera) * textureFootprint;
}

}  // namespace tandem
