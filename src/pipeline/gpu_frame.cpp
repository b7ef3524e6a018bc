#include "pipeline/gpu_frame.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "core/interrupt.h"

namespace tandem {

GpuFrame::GpuFrame(std::shared_ptr<GpuDevice> device)
    : device_(std::move(device)),
      memory_(*device_),
      commands_(*device_),
      uploads_(*device_),
      scene_(memory_) {}

GpuFrame::~GpuFrame() {
  kernels_.clear();
  for (auto& [name, c] : copies_) memory_.release(c.buffer);
  for (auto& [key, b] : scratch_) memory_.release(b);
  memory_.release(staging_);
  for (GpuBuffer& b : constants_) memory_.release(b);
}

GpuScene& GpuFrame::scene(const FrameScene& fs) {
  scene_.update(fs, uploads_);
  return scene_;
}

uint64_t GpuFrame::constants(const void* data, size_t bytes) {
  constexpr size_t kAlign = 16, kArenaBytes = size_t(1) << 16;
  size_t at = (constantsUsed_ + kAlign - 1) / kAlign * kAlign;
  // The next arena (made as large as needed) once this one is full: earlier addresses stay valid.
  while (constantsArena_ >= constants_.size() || at + bytes > constants_[constantsArena_].size) {
    if (constantsArena_ < constants_.size()) ++constantsArena_;
    at = 0;
    if (constantsArena_ == constants_.size())
      constants_.push_back(memory_.allocate(std::max(kArenaBytes, bytes), true));
    else if (constants_[constantsArena_].size < bytes) {
      memory_.release(constants_[constantsArena_]);
      constants_[constantsArena_] = memory_.allocate(bytes, true);
    }
  }
  GpuBuffer& arena = constants_[constantsArena_];
  std::memcpy(static_cast<char*>(arena.mapped) + at, data, bytes);
  constantsUsed_ = at + bytes;
  return arena.address + at;
}

const void* GpuFrame::constantsData(uint64_t address) const {
  for (const GpuBuffer& b : constants_)
    if (address >= b.address && address < b.address + b.size)
      return static_cast<const char*>(b.mapped) + (address - b.address);
  throw std::logic_error("GPU: not an address of this submission's constants");
}

void GpuFrame::dispatchInterruptibly(const GpuKernel& kernel, uint32_t x, uint32_t y,
                                     const void* push) {
  constexpr uint32_t kBands = 64;  // at most, per dispatch (two timestamps each)
  if (device_->info().hardware || y <= 1) {
    commands_.dispatch(kernel, x, y, 1, push);
    return;
  }
  const uint32_t rows = (y + kBands - 1) / kBands;
  for (uint32_t y0 = 0; y0 < y; y0 += rows) {
    if (y0 > 0) {
      commands_.checkpoint();
      pollInterrupt();
    }
    commands_.dispatch(kernel, x, std::min(rows, y - y0), 1, push, y0);
  }
}

void GpuFrame::dropScratch(const std::string& key) {
  auto it = scratch_.find(key);
  if (it == scratch_.end()) return;
  memory_.release(it->second);
  scratch_.erase(it);
}

const GpuBuffer& GpuFrame::scratch(const std::string& key, size_t bytes) {
  GpuBuffer& b = scratch_[key];
  if (b && b.size < bytes) memory_.release(b);
  if (!b) b = memory_.allocate(std::max<size_t>(bytes, 4), false);
  return b;
}

void GpuFrame::beginSubmission() {
  constantsArena_ = 0;
  constantsUsed_ = 0;
  after_.clear();
}

void GpuFrame::endSubmission() {
  std::vector<std::function<void()>> after;
  after.swap(after_);
  for (auto& f : after) f();
}

const GpuKernel& GpuFrame::kernel(const std::string& name, const uint32_t* spirv, size_t words,
                                  uint32_t pushBytes) {
  auto& k = kernels_[name];
  if (!k) k = std::make_unique<GpuKernel>(*device_, name, spirv, words, pushBytes);
  return *k;
}

bool GpuFrame::deviceNewer(const std::string& name) const {
  auto it = copies_.find(name);
  return it != copies_.end() && it->second.newer;
}

bool GpuFrame::onDevice(const std::string& name) const {
  auto it = copies_.find(name);
  return it != copies_.end() && it->second.current;
}

GpuFrame::Copy& GpuFrame::copyFor(const std::string& name, size_t bytes) {
  Copy& c = copies_[name];
  if (c.buffer && c.buffer.size < bytes) memory_.release(c.buffer);
  if (!c.buffer) c.buffer = memory_.allocate(bytes, false);
  return c;
}

GpuBuffer& GpuFrame::staging(size_t bytes) {
  if (staging_ && staging_.size < bytes) memory_.release(staging_);
  if (!staging_) staging_ = memory_.allocate(bytes, true);
  return staging_;
}

size_t GpuFrame::upload(const std::string& name, const Buffer& b) {
  if (onDevice(name)) return 0;
  const size_t bytes = b.data.size() * sizeof(float);
  Copy& c = copyFor(name, bytes);
  if (bytes) {
    GpuBuffer& s = staging(bytes);
    std::memcpy(s.mapped, b.data.data(), bytes);
    commands_.begin();
    commands_.copy(s, c.buffer, bytes);
    commands_.submit();
  }
  c.current = true;
  c.newer = false;
  return bytes;
}

size_t GpuFrame::download(const std::string& name, Buffer& b) {
  auto it = copies_.find(name);
  if (it == copies_.end() || !it->second.newer) return 0;
  const size_t bytes = b.data.size() * sizeof(float);
  if (bytes > it->second.buffer.size)
    throw std::logic_error("GPU copy of '" + name + "' is smaller than its host buffer");
  if (bytes) {
    GpuBuffer& s = staging(bytes);
    commands_.begin();
    commands_.copy(it->second.buffer, s, bytes);
    commands_.submit();
    std::memcpy(b.data.data(), s.mapped, bytes);
  }
  it->second.newer = false;
  return bytes;
}

const GpuBuffer& GpuFrame::write(const std::string& name, const Buffer& b) {
  Copy& c = copyFor(name, b.data.size() * sizeof(float));
  c.current = true;
  c.newer = true;
  return c.buffer;
}

const GpuBuffer& GpuFrame::read(const std::string& name) const {
  auto it = copies_.find(name);
  if (it == copies_.end() || !it->second.current)
    throw std::logic_error("buffer '" + name + "' was read on the GPU before it was moved there");
  return it->second.buffer;
}

void GpuFrame::hostWrote(const std::string& name) {
  auto it = copies_.find(name);
  if (it == copies_.end()) return;
  it->second.current = false;
  it->second.newer = false;
}

std::vector<std::string> GpuFrame::deviceOnly() const {
  std::vector<std::string> out;
  for (const auto& [name, c] : copies_)
    if (c.newer) out.push_back(name);
  return out;
}

void GpuFrame::drop(const std::string& name) {
  auto it = copies_.find(name);
  if (it == copies_.end()) return;
  memory_.release(it->second.buffer);
  copies_.erase(it);
}

void GpuFrame::forget() {
  for (auto& [name, c] : copies_) memory_.release(c.buffer);
  copies_.clear();
  for (auto& [key, b] : scratch_) memory_.release(b);
  scratch_.clear();
  ++generation_;
}

void GpuFrame::readBack(const GpuBuffer& b, size_t bytes, void* out) {
  if (bytes > b.size) throw std::logic_error("GPU: read back beyond a buffer's end");
  if (!bytes) return;
  GpuBuffer& s = staging(bytes);
  commands_.begin();
  commands_.copy(b, s, bytes);
  commands_.submit();
  std::memcpy(out, s.mapped, bytes);
}

}  // namespace tandem
