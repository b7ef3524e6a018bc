// libFuzzer target for the scene_file loader.
#include "fuzz_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return fuzzLoad(data, size, ".json");
}
