// Shared body of the loader fuzzers: write the input to a file with the right extension and
// load it; InputError is the expected outcome for bad input, anything else is a bug.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "scene/loaders.h"

inline int fuzzLoad(const uint8_t* data, size_t size, const char* ext) {
  static const std::string path = "/tmp/tandem_fuzz_" + std::to_string(getpid()) + ext;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  try {
    tandem::loadSceneByExtension(path);
  } catch (const tandem::InputError&) {
  }
  return 0;
}
