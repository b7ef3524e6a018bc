// What an experiment records about where it ran: CPU model and hardware threads, build type, the
// source tree's commit and the device its renders ran on, so a table can be traced back to its
// machine and code.
#pragma once
#include <string>

namespace tandem {

struct MachineInfo {
  std::string cpuModel;   // /proc/cpuinfo "model name", or "unknown"
  unsigned threads = 0;   // hardware threads
  std::string buildType;  // CMAKE_BUILD_TYPE of this binary
  std::string commit;     // `git describe --always --dirty` of the source tree, or "unknown"
  std::string device;     // where the renders ran: "CPU", or the GPU's name and kind
  std::string oneLine() const;
};

MachineInfo machineInfo();

}  // namespace tandem
