#include "pipeline/gpu_frame.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <iterator>
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
  graphicsRaster_.reset();
  for (auto& [name, c] : copies_) memory_.release(c.buffer);
  for (auto& [key, b] : scratch_) memory_.release(b);
  memory_.release(uploadStaging_);
  for (GpuBuffer& b : downloadStaging_) memory_.release(b);
  for (GpuBuffer& b : released_) memory_.release(b);
  for (GpuBuffer& b : constants_) memory_.release(b);
}

GpuGraphicsRaster& GpuFrame::graphicsRaster() {
  if (!graphicsRaster_) graphicsRaster_ = std::make_unique<GpuGraphicsRaster>(*device_);
  return *graphicsRaster_;
}

GpuScene& GpuFrame::scene(const FrameScene& fs) {
  // An update rewrites (and may reallocate) the scene's buffers, which work recorded in the open
  // batch may read: that work runs first.
  if (open_ && !scene_.current(fs)) commands_.checkpoint();
  scene_.update(fs, uploads_);
  return scene_;
}

void GpuFrame::release(GpuBuffer& b) {
  if (!b) return;
  if (open_) {
    released_.push_back(b);
    b = GpuBuffer{};
  } else {
    memory_.release(b);
  }
}

void GpuFrame::open() {
  if (open_) return;
  constantsArena_ = 0;
  constantsUsed_ = 0;
  downloadsUsed_ = 0;
  after_.clear();
  commands_.begin();
  open_ = true;
}

double GpuFrame::flush() {
  if (!open_) return 0;
  const auto t0 = std::chrono::steady_clock::now();
  open_ = false;
  try {
    commands_.submit();
  } catch (...) {
    after_.clear();
    throw;
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ++batches_;
  for (GpuBuffer& b : released_) memory_.release(b);
  released_.clear();
  std::vector<std::function<void()>> after;
  after.swap(after_);
  for (auto& f : after) f();
  return ms;
}

bool GpuFrame::abandon() {
  if (!open_) return false;  // nothing recorded is left unrun
  commands_.abandon();
  open_ = false;
  after_.clear();
  forget();
  for (GpuBuffer& b : released_) memory_.release(b);
  released_.clear();
  return true;
}

std::vector<std::function<void()>> GpuFrame::takeAfterSubmit(size_t first) {
  first = std::min(first, after_.size());
  std::vector<std::function<void()>> out(std::make_move_iterator(after_.begin() + long(first)),
                                         std::make_move_iterator(after_.end()));
  after_.resize(first);
  return out;
}

uint64_t GpuFrame::constants(const void* data, size_t bytes) {
  constexpr size_t kAlign = 16, kArenaBytes = size_t(1) << 16;
  size_t at = (constantsUsed_ + kAlign - 1) / kAlign * kAlign;
  // The next arena (made as large as needed) once this one is full: earlier addresses stay valid.
  while (constantsArena_ >= constants_.size() || at + bytes > constants_[constantsArena_].size) {
    if (constantsArena_ < constants_.size()) ++constantsArena_;
    at = 0;
    if (constantsArena_ == constants_.size())
      constants_.push_back(memory_.allocate(std::max(kArenaBytes, bytes), MemoryUse::Upload));
    else if (constants_[constantsArena_].size < bytes) {
      memory_.release(constants_[constantsArena_]);
      constants_[constantsArena_] = memory_.allocate(bytes, MemoryUse::Upload);
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
  release(it->second);
  scratch_.erase(it);
}

const GpuBuffer& GpuFrame::scratch(const std::string& key, size_t bytes) {
  GpuBuffer& b = scratch_[key];
  if (b && b.size < bytes) release(b);
  if (!b) b = memory_.allocate(std::max<size_t>(bytes, 4), MemoryUse::Device);
  return b;
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
  if (c.buffer && c.buffer.size < bytes) release(c.buffer);
  if (!c.buffer) c.buffer = memory_.allocate(bytes, MemoryUse::Device);
  return c;
}

GpuFrame::Copyback GpuFrame::recordCopyback(const GpuBuffer& src, size_t bytes) {
  open();
  if (downloadsUsed_ == downloadStaging_.size()) downloadStaging_.emplace_back();
  GpuBuffer& s = downloadStaging_[downloadsUsed_];
  if (s && s.size < bytes) memory_.release(s);  // last used by an earlier batch, which has run
  if (!s) s = memory_.allocate(bytes, MemoryUse::Readback);
  commands_.barrier();  // what the batch wrote so far
  Copyback c{downloadsUsed_++, 0, 0};
  c.t0 = commands_.timestamp();
  commands_.copy(src, s, bytes);
  c.t1 = commands_.timestamp();
  return c;
}

// An upload runs at once, on its own command buffer: the open batch, submitted later, reads it.
// Nothing recorded in the batch can be reading the copy it overwrites: a copy written there, or
// already current, is never uploaded to.
size_t GpuFrame::upload(const std::string& name, const Buffer& b) {
  if (onDevice(name)) return 0;
  const size_t bytes = b.data.size() * sizeof(float);
  Copy& c = copyFor(name, bytes);
  if (bytes) {
    if (uploadStaging_ && uploadStaging_.size < bytes) memory_.release(uploadStaging_);
    if (!uploadStaging_) uploadStaging_ = memory_.allocate(bytes, MemoryUse::Upload);
    std::memcpy(uploadStaging_.mapped, b.data.data(), bytes);
    uploads_.begin();
    uploads_.copy(uploadStaging_, c.buffer, bytes);
    uploads_.submit();
  }
  c.current = true;
  c.newer = false;
  return bytes;
}

namespace {
const GpuBuffer& newerCopy(const std::string& name, const GpuBuffer& copy, size_t bytes) {
  if (bytes > copy.size)
    throw std::logic_error("GPU copy of '" + name + "' is smaller than its host buffer");
  return copy;
}
}  // namespace

size_t GpuFrame::download(const std::string& name, Buffer& b) {
  auto it = copies_.find(name);
  if (it == copies_.end() || !it->second.newer) return 0;
  const size_t bytes = b.data.size() * sizeof(float);
  if (bytes) readBack(newerCopy(name, it->second.buffer, bytes), bytes, b.data.data());
  it->second.newer = false;
  return bytes;
}

size_t GpuFrame::queueDownload(const std::string& name, Buffer& b,
                               std::function<void(double ms)> done) {
  auto it = copies_.find(name);
  if (it == copies_.end() || !it->second.newer) return 0;
  const size_t bytes = b.data.size() * sizeof(float);
  if (!bytes) return 0;
  const Copyback c = recordCopyback(newerCopy(name, it->second.buffer, bytes), bytes);
  it->second.newer = false;
  afterSubmit([this, c, &b, bytes, done = std::move(done)] {
    const auto t0 = std::chrono::steady_clock::now();
    std::memcpy(b.data.data(), downloadStaging_[c.staging].mapped, bytes);
    const double hostMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (done) done(commands_.activeMs(c.t0, c.t1) + hostMs);
  });
  return bytes;
}

void GpuFrame::copyOnDevice(const std::string& from, const std::string& to, size_t bytes,
                            bool hostCurrent) {
  const GpuBuffer& src = read(from);
  if (bytes > src.size) throw std::logic_error("GPU: a copy of '" + from + "' beyond its end");
  open();
  Copy& c = copyFor(to, bytes);
  commands_.barrier();  // what the batch wrote to `from`
  commands_.copy(src, c.buffer, bytes);
  c.current = true;
  c.newer = !hostCurrent;
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
  release(it->second.buffer);
  copies_.erase(it);
}

void GpuFrame::forget() {
  for (auto& [name, c] : copies_) release(c.buffer);
  copies_.clear();
  for (auto& [key, b] : scratch_) release(b);
  scratch_.clear();
  ++generation_;
}

void GpuFrame::readBack(const GpuBuffer& b, size_t bytes, void* out) {
  if (bytes > b.size) throw std::logic_error("GPU: read back beyond a buffer's end");
  if (!bytes) return;
  const bool wasOpen = open_;
  const Copyback c = recordCopyback(b, bytes);
  if (wasOpen)
    commands_.checkpoint();  // the batch records on
  else
    flush();
  std::memcpy(out, downloadStaging_[c.staging].mapped, bytes);
  // Read, so free again: a batch reading back many times (a reference's batches of samples)
  // keeps one staging buffer, not one a read.
  if (wasOpen && c.staging + 1 == downloadsUsed_) --downloadsUsed_;
}

}  // namespace tandem
