// libFuzzer target for the gltf loader.
#include "fuzz_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return fuzzLoad(data, size, ".gltf");
}
