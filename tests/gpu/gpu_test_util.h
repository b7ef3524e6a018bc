// What the GPU tests share: the device they run on (what `--device gpu` would take, with the
// Vulkan validation layers on) or a skip saying why there is none.
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "core/error.h"
#include "gpu/gpu_device.h"

namespace tandem {

// The device the tests run on, or null with the reason in `why`.
inline std::shared_ptr<GpuDevice> testDevice(std::string* why) {
  setenv("TANDEM_VK_VALIDATION", "1", 0);  // before the first instance
  try {
    return GpuDevice::forChoice(DeviceChoice::Gpu, "test");
  } catch (const InputError& e) {
    *why = e.what();
    return nullptr;
  }
}

#define REQUIRE_GPU(dev)                                                                       \
  std::string why;                                                                             \
  std::shared_ptr<GpuDevice> dev = testDevice(&why);                                           \
  if (!dev) GTEST_SKIP() << "no Vulkan device: " << why;                                       \
  ASSERT_TRUE(dev->validating()) << "the Vulkan validation layers are not installed (package " \
                                    "vulkan-validationlayers): GPU tests run only with them";

inline void expectNoValidationMessages(const GpuDevice& dev) {
  for (const std::string& m : dev.validationMessages()) ADD_FAILURE() << "validation: " << m;
}

}  // namespace tandem
