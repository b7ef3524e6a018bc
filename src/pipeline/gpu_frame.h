// A renderer's GPU side: its command buffer, device memory and kernels, and where each named
// buffer's current value lives. Buffers live where they were written: the pipeline moves a buffer
// to the device before a GPU pass that declares it as an input, and back before a CPU pass (or
// the caller) reads it, each move a timing row with its bytes (Pipeline::execute).
//
// Consecutive GPU passes record into one batch, submitted once where the host needs what they
// computed (before a CPU pass, at the frame's end): a frame of GPU passes is one submission, not
// one per pass. Uploads go ahead of the batch on a command buffer of their own.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/buffer.h"
#include "gpu/gpu_commands.h"
#include "gpu/gpu_device.h"
#include "gpu/gpu_graphics_raster.h"
#include "gpu/gpu_kernel.h"
#include "gpu/gpu_memory.h"
#include "gpu/gpu_scene.h"

namespace tandem {

// The name under which last frame's value of buffer `name` (a history input) lives on the device.
inline std::string historyKey(const std::string& name) {
  return "history:" + name;
}

class GpuFrame {
 public:
  explicit GpuFrame(std::shared_ptr<GpuDevice> device);
  ~GpuFrame();
  GpuDevice& device() { return *device_; }
  GpuCommands& commands() { return commands_; }
  GpuMemory& memory() { return memory_; }
  // The kernel `name` built from `spirv` on first use, kept after.
  const GpuKernel& kernel(const std::string& name, const uint32_t* spirv, size_t words,
                          uint32_t pushBytes);
  // The graphics pipeline's visibility draw, made on first use (a GpuError where the device's
  // queue has no graphics).
  GpuGraphicsRaster& graphicsRaster();

  // The frame's scene on the device, brought up to `fs` first (its own submission: call it before
  // recording kernels that read it).
  GpuScene& scene(const FrameScene& fs);
  void sceneChanged() { scene_.invalidate(); }  // a scene (re)set, perhaps edited in place
  // A copy of `bytes` of `data` in device-readable memory for this batch's kernels (records too
  // large for push constants); its address. Valid until the next batch opens; host visible, so
  // what kernels write there reads back after a checkpoint or the flush (constantsData).
  uint64_t constants(const void* data, size_t bytes);
  // The host's view of constants at `address` (kernels may write there: counters read back).
  const void* constantsData(uint64_t address) const;
  // commands().dispatch over groups (x, y) for a kernel whose work is heavy (a ray per pixel and
  // more): on a CPU Vulkan, where one such dispatch of a large frame runs for seconds, in bands of
  // group rows submitted one by one, Ctrl-C (pollInterrupt) honoured between them; on a GPU whole.
  void dispatchInterruptibly(const GpuKernel& kernel, uint32_t x, uint32_t y, const void* push);
  // Work to do once the recorded commands completed (reading back counters), in the order given.
  void afterSubmit(std::function<void()> f) { after_.push_back(std::move(f)); }
  size_t afterSubmitCount() const { return after_.size(); }
  // The afterSubmit work queued from index `first` on, taken out (a pass's, which the pipeline
  // runs with that pass's rays and parts).
  std::vector<std::function<void()>> takeAfterSubmit(size_t first);

  // The batch: begun if none is open (its constants start afresh).
  void open();
  bool isOpen() const { return open_; }
  uint64_t batches() const { return batches_; }  // flushed so far
  // Submits the batch, waits, then runs its afterSubmit work in order and frees what was released
  // while it was open; the wall milliseconds of the submission and wait (0: none was open).
  double flush();
  // An exception while recording: the batch and its afterSubmit work dropped, and every device
  // copy forgotten (what the batch was to write was never computed). Whether a batch was open.
  bool abandon();

  // A device buffer of at least `bytes` kept under `key` across frames for one pass's own use (a
  // visibility buffer, a queue): never moved, its contents whatever the pass left there.
  const GpuBuffer& scratch(const std::string& key, size_t bytes);
  // Scratch `key` freed at once: nothing recorded and not yet run may read it.
  void dropScratch(const std::string& key);
  // Changes with forget(): scratch a pass filled in an earlier generation is gone.
  uint64_t generation() const { return generation_; }
  // The first `bytes` of device buffer `b` into `out` (its own submission, between frames).
  void readBack(const GpuBuffer& b, size_t bytes, void* out);

  // Whether the device holds a newer value of `name` than the host.
  bool deviceNewer(const std::string& name) const;
  // Whether the device holds `name`'s current value (uploaded, or written there).
  bool onDevice(const std::string& name) const;
  // Makes the device copy of host buffer `b` (called `name`) current; the bytes moved (0 when it
  // already was).
  size_t upload(const std::string& name, const Buffer& b);
  // Makes the host copy current (b must have the device copy's size); the bytes moved. Inside a
  // batch, a checkpoint: what was recorded runs, and recording goes on.
  size_t download(const std::string& name, Buffer& b);
  // The same, done when the batch is flushed: b (which must live until then) holds the value
  // after flush(), and then `done` gets the milliseconds the move took (the GPU's copy and the
  // host's). The bytes to move.
  size_t queueDownload(const std::string& name, Buffer& b, std::function<void(double ms)> done);
  // Records in the batch a copy of `from`'s current device value into `to` (`bytes` of it): `to`
  // is current on the device, and newer than the host's unless `hostCurrent` (the host holds the
  // same value). History stays on the device this way (historyKey), moved only if the host reads
  // it.
  void copyOnDevice(const std::string& from, const std::string& to, size_t bytes, bool hostCurrent);
  // The device buffer that will hold `name`'s new value (b's size), the host's copy now stale.
  const GpuBuffer& write(const std::string& name, const Buffer& b);
  // The device copy of `name` (which must be current there).
  const GpuBuffer& read(const std::string& name) const;
  // A host write: the device copy, if any, is stale.
  void hostWrote(const std::string& name);
  // Names whose newest value is on the device only.
  std::vector<std::string> deviceOnly() const;
  void drop(const std::string& name);  // the device copy of `name` dropped (no longer produced)
  void forget();  // every device copy and scratch buffer dropped (a pipeline switch)

 private:
  struct Copy {
    GpuBuffer buffer;
    bool current = false;  // holds the buffer's current value
    bool newer = false;    // ... which the host does not have
  };
  Copy& copyFor(const std::string& name, size_t bytes);
  // Records the copy of `src` into staging of its own (one buffer per copy of the batch), timed.
  struct Copyback {
    size_t staging;  // in downloadStaging_
    uint32_t t0, t1;
  };
  Copyback recordCopyback(const GpuBuffer& src, size_t bytes);
  // b's memory given back, once no recorded command can use it (after the flush).
  void release(GpuBuffer& b);
  std::shared_ptr<GpuDevice> device_;
  GpuMemory memory_;
  GpuCommands commands_;
  GpuCommands uploads_;  // the scene's and uploads, submitted ahead of the open batch
  GpuScene scene_;
  std::unique_ptr<GpuGraphicsRaster> graphicsRaster_;
  GpuBuffer uploadStaging_;
  std::vector<GpuBuffer> downloadStaging_;  // used in turn each batch
  size_t downloadsUsed_ = 0;
  std::vector<GpuBuffer> released_;  // freed when the batch has run
  bool open_ = false;
  uint64_t batches_ = 0;
  std::vector<GpuBuffer> constants_;  // arenas, filled in turn each submission
  size_t constantsArena_ = 0, constantsUsed_ = 0;
  uint64_t generation_ = 0;
  std::vector<std::function<void()>> after_;
  std::map<std::string, Copy> copies_;
  std::map<std::string, GpuBuffer> scratch_;
  std::map<std::string, std::unique_ptr<GpuKernel>> kernels_;
};

}  // namespace tandem
