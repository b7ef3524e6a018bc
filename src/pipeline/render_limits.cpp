#include "pipeline/render_limits.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace tandem {

void checkFrameSize(const std::string& source, const std::string& widthField,
                    const std::string& heightField, double width, double height, bool stereo) {
  if (!(width >= 1 && width <= 16384))
    throw InputError(source, widthField, "must be in [1, 16384]");
  if (!(height >= 1 && height <= 16384))
    throw InputError(source, heightField, "must be in [1, 16384]");
  const double need = width * height * (stereo ? 2.0 : 1.0) * 175.0;
  const double have = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (have > 0 && need > 0.9 * have) {
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "%.0f x %.0f%s needs about %.1f GiB for its buffers; this machine has %.1f GiB",
                  width, height, stereo ? " (stereo)" : "", need / 1073741824.0,
                  have / 1073741824.0);
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
