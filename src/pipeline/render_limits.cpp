#include "pipeline/render_limits.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "raster/shadow_maps.h"
#include "scene/scene.h"

namespace tandem {

namespace {

constexpr double kFrameBytesPerPixel = 175.0;  // G-buffer, history, outputs
constexpr double kBytesPerTriangle = 160.0;    // world-space copy and ray-tracing hierarchy
constexpr double kBytesPerShadowTexel = 6.0;   // depth, casters, conservative depth, copies
constexpr double kGiB = 1073741824.0;

double physicalMemory() {
  return double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
}

}  // namespace

MemoryNeed memoryNeed(const Scene& scene, double width, double height, bool stereo) {
  MemoryNeed n;
  n.geometry = double(scene.memoryBytes()) + double(scene.triangleCount()) * kBytesPerTriangle;
  n.buffers = width * height * (stereo ? 2.0 : 1.0) * kFrameBytesPerPixel;
  for (const Light& l : scene.lights)
    if (l.castsShadows) {
      // Each map size a pipeline asks for is budgeted alone; one size is the common case.
      n.shadowMaps = kMaxShadowTexels * kBytesPerShadowTexel;
      break;
    }
  return n;
}

void checkSceneFits(const std::string& source, const std::string& field, const Scene& scene,
                    double width, double height, bool stereo, double haveBytes) {
  const double have = haveBytes > 0 ? haveBytes : physicalMemory();
  const MemoryNeed n = memoryNeed(scene, width, height, stereo);
  if (!(have > 0) || n.total() <= 0.9 * have) return;
  char msg[400];
  std::snprintf(msg, sizeof msg,
                "'%s' needs about %.1f GiB to render at %.0f x %.0f%s (geometry %.1f GiB with its "
                "world-space copy and ray-tracing hierarchy, buffers %.1f GiB, shadow maps %.1f "
                "GiB); this machine has %.1f GiB",
                scene.name.c_str(), n.total() / kGiB, width, height, stereo ? " (stereo)" : "",
                n.geometry / kGiB, n.buffers / kGiB, n.shadowMaps / kGiB, have / kGiB);
  throw InputError(source, field, msg);
}

void checkFrameSize(const std::string& source, const std::string& widthField,
                    const std::string& heightField, double width, double height, bool stereo) {
  if (!(width >= 1 && width <= 16384))
    throw InputError(source, widthField, "must be in [1, 16384]");
  if (!(height >= 1 && height <= 16384))
    throw InputError(source, heightField, "must be in [1, 16384]");
  const double need = width * height * (stereo ? 2.0 : 1.0) * kFrameBytesPerPixel;
  const double have = physicalMemory();
  if (have > 0 && need > 0.9 * have) {
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "%.0f x %.0f%s needs about %.1f GiB for its buffers; this machine has %.1f GiB",
                  width, height, stereo ? " (stereo)" : "", need / kGiB, have / kGiB);
    throw InputError(source, widthField + " / " + heightField, msg);
  }
}

void checkShutter(const std::string& source, const std::string& field, double seconds) {
  if (!(seconds >= 0 && seconds <= 1000))
    throw InputError(source, field, "must be in [0, 1000] seconds");
}

void checkSpp(const std::string& source, const std::string& field, double spp) {
  if (!(spp >= 1 && spp <= double(1 << 20)))
    throw InputError(source, field, "must be in [1, 1048576]");
}

void checkTime(const std::string& source, const std::string& field, double seconds) {
  if (!std::isfinite(seconds)) throw InputError(source, field, "must be finite");
}

}  // namespace tandem
