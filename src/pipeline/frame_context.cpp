#include "pipeline/frame_context.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include "pipeline/gpu_frame.h"
#include "pipeline/pass.h"
#include "shading/surface_resolve.h"

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

int FrameContext::shadowMapResolution(int size, bool fit) const {
  if (!fit) return size;
  int side = 1;
  for (const View& v : views) side = std::max({side, v.width(), v.height()});
  return std::max(int(std::bit_ceil(unsigned(side))), size);
}

ShadowMaps& FrameContext::shadowMaps(int resolution, const std::vector<uint8_t>* wanted) {
  std::unique_ptr<ShadowMaps>& m = shadowMaps_[resolution];
  if (!m) m = std::make_unique<ShadowMaps>();
  m->update(frame, resolution, wanted);
  return *m;
}

ShadowMaps& FrameContext::deviceShadowMaps(int resolution) {
  std::unique_ptr<ShadowMaps>& m = deviceShadowMaps_[resolution];
  if (!m) m = std::make_unique<ShadowMaps>();
  return *m;
}

const ShadowMaps* FrameContext::heldShadowMaps(int resolution, bool device) const {
  const auto& held = device ? deviceShadowMaps_ : shadowMaps_;
  auto it = held.find(resolution);
  return it == held.end() ? nullptr : it->second.get();
}

namespace {

enum class Access { Input, History, Output };

// The declaration of `slot` as `pass` uses it; a logic_error naming both when there is none.
BufferSlot declared(const Pass& pass, const std::string& slot, Access access) {
  const std::optional<BufferSlot> s =
      access == Access::Output ? pass.outputSlot(slot) : pass.inputSlot(slot);
  const char* as = access == Access::Output    ? "output"
                   : access == Access::History ? "history input"
                                               : "input";
  if (!s)
    throw std::logic_error("pass '" + pass.name() + "' uses slot '" + slot +
                           "', which it does not declare as an " + as);
  if (access != Access::Output && s->history != (access == Access::History))
    throw std::logic_error("pass '" + pass.name() + "' reads slot '" + slot + "' as " +
                           (s->history ? "this frame's value" : "last frame's value") +
                           ", but declares it as " +
                           (s->history ? "a history input" : "this frame's input"));
  return *s;
}

}  // namespace

Buffer& FrameContext::shapedOutput(const Pass& pass, const std::string& slot, int w, int h) {
  const std::optional<BufferSlot> s = declared(pass, slot, Access::Output);
  if (s->extent.scale != Extent::Scale::Any) s->extent.resolve(width, height, w, h);
  Buffer& b = buffers[pass.bufferName(slot)];
  if (b.width != w || b.height != h || b.channels != s->channels) b = Buffer(w, h, s->channels);
  b.kind = s->kind;
  return b;
}

Buffer& FrameContext::output(const Pass& pass, const std::string& slot, int w, int h) {
  Buffer& b = shapedOutput(pass, slot, w, h);
  const std::string& name = pass.bufferName(slot);
  if (gpu) {  // the host writes it now: contents kept are the newest, the device copy is stale
    if (gpu->deviceNewer(name)) gpu->download(name, b);
    gpu->hostWrote(name);
  }
  return b;
}

uint64_t FrameContext::deviceInput(const Pass& pass, const std::string& slot) const {
  declared(pass, slot, Access::Input);
  if (!gpu) throw std::logic_error("pass '" + pass.name() + "' ran on the GPU without one");
  return gpu->read(pass.bufferName(slot)).address;
}

uint64_t FrameContext::devicePrevious(const Pass& pass, const std::string& slot) const {
  if (!previous(pass, slot)) return 0;
  if (!gpu) throw std::logic_error("pass '" + pass.name() + "' ran on the GPU without one");
  return gpu->read(historyKey(pass.bufferName(slot))).address;
}

uint64_t FrameContext::deviceOutput(const Pass& pass, const std::string& slot, int w, int h) {
  if (!gpu) throw std::logic_error("pass '" + pass.name() + "' ran on the GPU without one");
  // The device writes it: the host buffer only gives the shape (its contents are stale).
  const Buffer& b = shapedOutput(pass, slot, w, h);
  return gpu->write(pass.bufferName(slot), b).address;
}

uint64_t FrameContext::deviceOutputIfConsumed(const Pass& pass, const std::string& slot) {
  if (isConsumed(pass, slot)) return deviceOutput(pass, slot);
  buffers.erase(pass.bufferName(slot));
  if (gpu) gpu->drop(pass.bufferName(slot));
  return 0;
}

void FrameContext::report(const Pass& pass, const std::string& name, double value) {
  if (!pass.declaresCounter(name))
    throw std::logic_error("pass '" + pass.name() + "' reports counter '" + name +
                           "', which it does not declare");
  counters[name] = value;
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
  declared(pass, slot, Access::Output);
  const std::string& name = pass.bufferName(slot);
  return keepAllOutputs || consumed.count(name) || wanted.count(name);
}

Buffer* FrameContext::outputIfConsumed(const Pass& pass, const std::string& slot) {
  if (isConsumed(pass, slot)) return &output(pass, slot);
  buffers.erase(pass.bufferName(slot));
  return nullptr;
}

const Buffer& FrameContext::input(const Pass& pass, const std::string& slot) const {
  declared(pass, slot, Access::Input);
  return input(pass.bufferName(slot));
}

const Buffer* FrameContext::previous(const Pass& pass, const std::string& slot) const {
  declared(pass, slot, Access::History);
  auto it = history.find(pass.bufferName(slot));
  return it == history.end() ? nullptr : &it->second;
}

const Buffer* FrameContext::optionalInput(const Pass& pass, const std::string& slot) const {
  declared(pass, slot, Access::Input);
  auto it = buffers.find(pass.bufferName(slot));
  return it == buffers.end() ? nullptr : &it->second;
}

const Buffer& FrameContext::input(const std::string& name) const {
  auto it = buffers.find(name);
  // Wiring was checked when the pipeline loaded: a missing buffer is a read nobody declared.
  if (it == buffers.end()) throw std::logic_error("no buffer '" + name + "' in this frame");
  return it->second;
}

float FrameContext::pixelSpread(const View& view) const {
  return pixelSpreadAngle(view.camera) * textureFootprint;
}

}  // namespace tandem
