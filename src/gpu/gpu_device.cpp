#include "gpu/gpu_device.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/error.h"

namespace tandem {

void checkVk(VkResult r, const char* call) {
  if (r == VK_SUCCESS) return;
  const char* name = r == VK_ERROR_OUT_OF_DEVICE_MEMORY    ? "out of device memory"
                     : r == VK_ERROR_OUT_OF_HOST_MEMORY    ? "out of host memory"
                     : r == VK_ERROR_DEVICE_LOST           ? "device lost"
                     : r == VK_ERROR_INITIALIZATION_FAILED ? "initialization failed"
                     : r == VK_ERROR_LAYER_NOT_PRESENT     ? "layer not present"
                     : r == VK_ERROR_EXTENSION_NOT_PRESENT ? "extension not present"
                     : r == VK_ERROR_FEATURE_NOT_PRESENT   ? "feature not present"
                     : r == VK_ERROR_INCOMPATIBLE_DRIVER   ? "incompatible driver"
                                                           : "error";
  throw GpuError(std::string("GPU: ") + call + " failed: " + name + " (VkResult " +
                 std::to_string(int(r)) + ")");
}

DeviceChoice parseDeviceChoice(const std::string& text, const std::string& source,
                               const std::string& field) {
  if (text == "auto") return DeviceChoice::Auto;
  if (text == "cpu") return DeviceChoice::Cpu;
  if (text == "gpu") return DeviceChoice::Gpu;
  throw InputError(source, field, "expected auto, cpu or gpu, got '" + text + "'");
}

const char* deviceChoiceName(DeviceChoice c) {
  return c == DeviceChoice::Auto ? "auto" : c == DeviceChoice::Cpu ? "cpu" : "gpu";
}

std::string GpuDeviceInfo::apiText() const {
  return std::to_string(VK_API_VERSION_MAJOR(apiVersion)) + "." +
         std::to_string(VK_API_VERSION_MINOR(apiVersion)) + "." +
         std::to_string(VK_API_VERSION_PATCH(apiVersion));
}

namespace {

// The one Vulkan instance of the process (volk's function pointers are process-wide), with the
// validation layers when TANDEM_VK_VALIDATION=1 and what they printed.
struct Instance {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  std::string whyNone;  // set when there is no usable loader or instance
  std::mutex mutex;
  std::vector<std::string> messages;
};

VKAPI_ATTR VkBool32 VKAPI_CALL recordMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void* user) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  auto* in = static_cast<Instance*>(user);
  const std::string text = data && data->pMessage ? data->pMessage : "(no message)";
  std::fprintf(stderr, "tandem: Vulkan validation: %s\n", text.c_str());
  const std::lock_guard<std::mutex> lock(in->mutex);
  in->messages.push_back(text);
  return VK_FALSE;
}

bool hasLayer(const char* name) {
  uint32_t n = 0;
  if (vkEnumerateInstanceLayerProperties(&n, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

Instance& instance() {
  // Never destroyed: drivers' own exit handlers may still call into it.
  static Instance& in = *[] {
    auto* made = new Instance;
    Instance& r = *made;
    if (volkInitialize() != VK_SUCCESS) {
      r.whyNone = "no Vulkan loader (libvulkan.so.1) on this machine";
      return made;
    }
    if (volkGetInstanceVersion() < VK_API_VERSION_1_3) {
      r.whyNone = "the Vulkan loader is older than 1.3";
      return made;
    }
    const char* v = std::getenv("TANDEM_VK_VALIDATION");
    const bool validate = v && std::strcmp(v, "1") == 0 && hasLayer("VK_LAYER_KHRONOS_validation");
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "tandem";
    app.apiVersion = VK_API_VERSION_1_3;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkInstanceCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ci.pApplicationInfo = &app;
    if (validate) {
      ci.enabledLayerCount = 1;
      ci.ppEnabledLayerNames = &layer;
      ci.enabledExtensionCount = 1;
      ci.ppEnabledExtensionNames = &ext;
    }
    if (vkCreateInstance(&ci, nullptr, &r.instance) != VK_SUCCESS) {
      r.whyNone = "no Vulkan 1.3 instance could be created (no driver?)";
      r.instance = VK_NULL_HANDLE;
      return made;
    }
    volkLoadInstanceOnly(r.instance);
    return made;
  }();
  // The messenger needs the instance's final address (the callback's user pointer).
  static const bool messenger = [] {
    Instance& i = in;
    const char* v = std::getenv("TANDEM_VK_VALIDATION");
    if (i.instance && v && std::strcmp(v, "1") == 0 && vkCreateDebugUtilsMessengerEXT) {
      VkDebugUtilsMessengerCreateInfoEXT dm{};
      dm.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
      dm.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
      dm.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
      dm.pfnUserCallback = recordMessage;
      dm.pUserData = &i;
      vkCreateDebugUtilsMessengerEXT(i.instance, &dm, nullptr, &i.messenger);
    }
    return true;
  }();
  (void)messenger;
  return in;
}

std::string typeName(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance inst) {
  uint32_t n = 0;
  if (vkEnumeratePhysicalDevices(inst, &n, nullptr) != VK_SUCCESS) return {};
  std::vector<VkPhysicalDevice> out(n);
  vkEnumeratePhysicalDevices(inst, &n, out.data());
  out.resize(n);
  return out;
}

// A queue family with compute and timestamps, or -1.
int computeFamily(VkPhysicalDevice pd) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> fams(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, fams.data());
  for (uint32_t i = 0; i < n; ++i)
    if ((fams[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && fams[i].timestampValidBits > 0)
      return int(i);
  return -1;
}

GpuDeviceInfo describe(VkPhysicalDevice pd) {
  auto m4 = vkStruct<VkPhysicalDeviceMaintenance4Properties>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES);
  auto m3 = vkStruct<VkPhysicalDeviceMaintenance3Properties>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES, &m4);
  auto p12 = vkStruct<VkPhysicalDeviceVulkan12Properties>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES, &m3);
  auto p11 = vkStruct<VkPhysicalDeviceVulkan11Properties>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES, &p12);
  auto props =
      vkStruct<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p11);
  vkGetPhysicalDeviceProperties2(pd, &props);
  auto f13 = vkStruct<VkPhysicalDeviceVulkan13Features>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
  auto f12 = vkStruct<VkPhysicalDeviceVulkan12Features>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13);
  auto feats =
      vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12);
  vkGetPhysicalDeviceFeatures2(pd, &feats);
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(pd, &mem);

  GpuDeviceInfo info;
  info.name = props.properties.deviceName;
  info.type = typeName(props.properties.deviceType);
  info.driver = std::string(p12.driverName) + " " + p12.driverInfo;
  info.apiVersion = props.properties.apiVersion;
  info.hardware = props.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ||
                  props.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ||
                  props.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU;
  info.subgroupSize = p11.subgroupSize;
  info.maxBufferBytes = std::min(m3.maxMemoryAllocationSize, m4.maxBufferSize);
  for (uint32_t h = 0; h < mem.memoryHeapCount; ++h)
    if (mem.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      info.deviceLocalBytes = std::max<uint64_t>(info.deviceLocalBytes, mem.memoryHeaps[h].size);
  std::string missing;
  auto need = [&](bool ok, const char* what) {
    if (!ok) missing += (missing.empty() ? "" : ", ") + std::string(what);
  };
  need(info.apiVersion >= VK_API_VERSION_1_3, "Vulkan 1.3");
  need(computeFamily(pd) >= 0, "a compute queue with timestamps");
  need(feats.features.shaderInt64, "shaderInt64");
  need(f12.shaderBufferInt64Atomics, "shaderBufferInt64Atomics");
  info.float64 = feats.features.shaderFloat64;
  need(f12.bufferDeviceAddress, "bufferDeviceAddress");
  need(f12.scalarBlockLayout, "scalarBlockLayout");
  need(f13.synchronization2, "synchronization2");
  need(f13.maintenance4, "maintenance4");
  need(props.properties.limits.timestampComputeAndGraphics || computeFamily(pd) >= 0, "timestamps");
  info.usable = missing.empty();
  info.missing = missing;
  return info;
}

// The device `choice` opens: the first usable hardware GPU (discrete first), else for Gpu the
// first usable CPU Vulkan; -1 when none.
int pick(const std::vector<GpuDeviceInfo>& devices, DeviceChoice choice) {
  int best = -1;
  for (size_t i = 0; i < devices.size(); ++i) {
    const GpuDeviceInfo& d = devices[i];
    if (!d.usable || !d.hardware) continue;
    if (best < 0 || (d.type == "discrete GPU" && devices[size_t(best)].type != "discrete GPU"))
      best = int(i);
  }
  if (best >= 0 || choice != DeviceChoice::Gpu) return best;
  for (size_t i = 0; i < devices.size(); ++i)
    if (devices[i].usable) return int(i);
  return -1;
}

}  // namespace

std::vector<GpuDeviceInfo> listGpuDevices(std::string* whyNone) {
  Instance& in = instance();
  if (!in.instance) {
    if (whyNone) *whyNone = in.whyNone;
    return {};
  }
  std::vector<GpuDeviceInfo> out;
  for (VkPhysicalDevice pd : physicalDevices(in.instance)) out.push_back(describe(pd));
  if (out.empty() && whyNone) *whyNone = "the Vulkan loader found no device (no driver installed)";
  return out;
}

std::shared_ptr<GpuDevice> GpuDevice::forChoice(DeviceChoice choice, const std::string& source) {
  if (choice == DeviceChoice::Cpu) return nullptr;
  static std::mutex mutex;
  static std::shared_ptr<GpuDevice> opened;
  static bool hardwareChecked = false;
  static int hardwareIndex = -1;
  const std::lock_guard<std::mutex> lock(mutex);
  std::string why;
  const std::vector<GpuDeviceInfo> devices = listGpuDevices(&why);
  const int index = pick(devices, choice);
  if (!hardwareChecked) {
    hardwareIndex = pick(devices, DeviceChoice::Auto);
    hardwareChecked = true;
  }
  if (index < 0) {
    if (choice == DeviceChoice::Auto) return nullptr;
    std::string detail = why;
    for (const GpuDeviceInfo& d : devices)
      detail += (detail.empty() ? "" : "; ") + d.name + " lacks " + d.missing;
    throw InputError(source, "device",
                     "gpu was asked for but no usable Vulkan device was found" +
                         (detail.empty() ? std::string() : " (" + detail + ")"));
  }
  if (!opened) opened = std::shared_ptr<GpuDevice>(new GpuDevice(size_t(index)));
  // One device per process: a later Auto that found no hardware GPU still gets no device.
  if (choice == DeviceChoice::Auto && hardwareIndex < 0) return nullptr;
  return opened;
}

GpuDevice::GpuDevice(size_t index) {
  Instance& in = instance();
  if (!in.instance) throw GpuError("GPU: " + in.whyNone);
  const std::vector<VkPhysicalDevice> pds = physicalDevices(in.instance);
  if (index >= pds.size()) throw GpuError("GPU: no Vulkan device " + std::to_string(index));
  physical_ = pds[index];
  info_ = describe(physical_);
  if (!info_.usable) throw GpuError("GPU: " + info_.name + " lacks " + info_.missing);
  family_ = uint32_t(computeFamily(physical_));
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physical_, &props);
  timestampPeriod_ = props.limits.timestampPeriod;

  const float priority = 1.0f;
  auto q = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  q.queueFamilyIndex = family_;
  q.queueCount = 1;
  q.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan13Features f13{};
  f13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  f13.synchronization2 = VK_TRUE;
  f13.maintenance4 = VK_TRUE;      // glslc's SPIR-V for Vulkan 1.3 declares LocalSizeId
  f13.dynamicRendering = VK_TRUE;  // the graphics rasterizer (core in 1.3: every device has it)
  VkPhysicalDeviceVulkan12Features f12{};
  f12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  f12.bufferDeviceAddress = VK_TRUE;
  f12.scalarBlockLayout = VK_TRUE;
  f12.shaderBufferInt64Atomics = VK_TRUE;  // the rasterizer's visibility buffer
  f12.pNext = &f13;
  VkPhysicalDeviceFeatures2 feats{};
  feats.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  feats.features.shaderInt64 = VK_TRUE;
  feats.features.shaderFloat64 = info_.float64 ? VK_TRUE : VK_FALSE;
  feats.pNext = &f12;
  VkDeviceCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  ci.pNext = &feats;
  ci.queueCreateInfoCount = 1;
  ci.pQueueCreateInfos = &q;
  checkVk(vkCreateDevice(physical_, &ci, nullptr, &device_), "vkCreateDevice");
  volkLoadDevice(device_);
  vkGetDeviceQueue(device_, family_, 0, &queue_);
  VkFenceCreateInfo fi{};
  fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  checkVk(vkCreateFence(device_, &fi, nullptr, &fence_), "vkCreateFence");
  messenger_ = in.messenger;
}

GpuDevice::~GpuDevice() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyFence(device_, fence_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
}

void GpuDevice::submitAndWait(VkCommandBuffer cb) {
  const std::lock_guard<std::mutex> lock(queueMutex_);
  VkSubmitInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cb;
  checkVk(vkResetFences(device_, 1, &fence_), "vkResetFences");
  checkVk(vkQueueSubmit(queue_, 1, &si, fence_), "vkQueueSubmit");
  checkVk(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  ++submissions_;
}

std::vector<std::string> GpuDevice::validationMessages() const {
  Instance& in = instance();
  const std::lock_guard<std::mutex> lock(in.mutex);
  return in.messages;
}

}  // namespace tandem
