#include "eval/experiments/machine_info.h"

#include <cstdio>
#include <fstream>
#include <thread>

#include "pipeline/renderer.h"

#ifndef TANDEM_SOURCE_DIR
#define TANDEM_SOURCE_DIR "."
#endif
#ifndef TANDEM_BUILD_TYPE
#define TANDEM_BUILD_TYPE "unknown"
#endif

namespace tandem {

namespace {

std::string readCpuModel() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) {
      size_t colon = line.find(':');
      if (colon != std::string::npos && colon + 2 <= line.size()) return line.substr(colon + 2);
    }
  return "unknown";
}

std::string readCommit() {
  std::string cmd =
      std::string("git -C '") + TANDEM_SOURCE_DIR + "' describe --always --dirty 2>/dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return "unknown";
  char buf[128] = {};
  std::string out;
  if (std::fgets(buf, sizeof buf, p)) out = buf;
  pclose(p);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out.empty() ? "unknown" : out;
}

}  // namespace

MachineInfo machineInfo() {
  MachineInfo m;
  m.cpuModel = readCpuModel();
  m.threads = std::thread::hardware_concurrency();
  m.buildType = TANDEM_BUILD_TYPE;
  m.commit = readCommit();
  const std::shared_ptr<GpuDevice> gpu = defaultRenderDevice();
  m.device = gpu ? gpu->info().name + " (" + gpu->info().type + ")" : "CPU";
  return m;
}

std::string MachineInfo::oneLine() const {
  return cpuModel + ", " + std::to_string(threads) + " hardware threads; " + buildType +
         " build; commit " + commit + "; device " + device;
}

}  // namespace tandem
