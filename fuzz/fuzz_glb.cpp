// libFuzzer target for the binary glTF (.glb) path: header and chunk parsing, the preflight's
// GLB rebuild for Draco primitives, embedded buffers.
#include "fuzz_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return fuzzLoad(data, size, ".glb");
}
