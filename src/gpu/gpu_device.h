// The Vulkan compute device: Vulkan 1.3 loaded at run time (volk), so Tandem starts on a machine
// with no Vulkan at all. A device is opened once per process and shared (instance creation costs
// a few hundred milliseconds, more with the validation layers); every Renderer on the GPU records
// into its own command buffers on it.
#pragma once
#include <volk.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace tandem {

// A Vulkan call that failed: the call and its VkResult.
class GpuError : public std::runtime_error {
 public:
  explicit GpuError(const std::string& what) : std::runtime_error(what) {}
};
void checkVk(VkResult r, const char* call);

// A Vulkan structure of type T, zeroed, with its sType and pNext chain set.
template <class T>
T vkStruct(VkStructureType type, void* next = nullptr) {
  T v{};
  v.sType = type;
  v.pNext = next;
  return v;
}

// Where passes run: `auto` takes a hardware GPU when there is one and the CPU otherwise; `gpu`
// also takes a CPU Vulkan (lavapipe), so CI can run the GPU code; `cpu` never opens Vulkan.
enum class DeviceChoice { Auto, Cpu, Gpu };
// Parses "auto", "cpu" or "gpu" (InputError naming source and field otherwise).
DeviceChoice parseDeviceChoice(const std::string& text, const std::string& source,
                               const std::string& field);
const char* deviceChoiceName(DeviceChoice c);

struct GpuDeviceInfo {
  std::string name;
  std::string type;  // "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other"
  std::string driver;
  uint32_t apiVersion = 0;
  bool hardware = false;  // a GPU, not a CPU implementation
  bool usable = false;    // Vulkan 1.3 with a compute queue and what Tandem needs
  std::string missing;    // why not usable
  uint64_t deviceLocalBytes = 0;
  uint64_t maxBufferBytes = 0;  // the largest one buffer or allocation may be
  uint32_t subgroupSize = 0;
  bool float64 = false;  // shaderFloat64: the rasterizer solves depth planes in double as the CPU
  std::string apiText() const;  // "1.3.230"
};

// What the Vulkan loader sees; empty with `whyNone` set when there is no loader or no device.
std::vector<GpuDeviceInfo> listGpuDevices(std::string* whyNone = nullptr);

class GpuDevice {
 public:
  // The process's device for `choice`: null for Cpu, and for Auto when no hardware GPU is usable;
  // for Gpu an InputError naming `source` and the field "device" when none is usable. Opened
  // once, shared after.
  static std::shared_ptr<GpuDevice> forChoice(DeviceChoice choice, const std::string& source);
  ~GpuDevice();
  GpuDevice(const GpuDevice&) = delete;
  GpuDevice& operator=(const GpuDevice&) = delete;

  const GpuDeviceInfo& info() const { return info_; }
  VkDevice device() const { return device_; }
  VkPhysicalDevice physical() const { return physical_; }
  uint32_t queueFamily() const { return family_; }
  float timestampPeriodNs() const { return timestampPeriod_; }
  // Submits and waits (the queue is shared: one submission at a time).
  void submitAndWait(VkCommandBuffer cb);
  // Submissions so far (each one a wait for the device: a frame should make few).
  uint64_t submissions() const { return submissions_.load(); }
  // Messages the validation layers printed (on when TANDEM_VK_VALIDATION=1); tests fail on any.
  std::vector<std::string> validationMessages() const;
  bool validating() const { return messenger_ != VK_NULL_HANDLE; }

  // Opens `physical` (the index listGpuDevices gives); public for tests.
  explicit GpuDevice(size_t index);

 private:
  GpuDeviceInfo info_;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  uint32_t family_ = 0;
  float timestampPeriod_ = 1;
  std::mutex queueMutex_;
  std::atomic<uint64_t> submissions_{0};
};

}  // namespace tandem
