#include "core/assets.h"

#include <cstdlib>

namespace tandem {

std::string assetsDir() {
  const char* env = std::getenv("TANDEM_ASSETS");
  if (env && *env) return env;
  return TANDEM_DEFAULT_ASSETS;
}

bool isAssetPath(const std::string& path) {
  return path.rfind(kAssetsPrefix, 0) == 0;
}

std::string expandAssetPath(const std::string& path) {
  if (!isAssetPath(path)) return path;
  return assetsDir() + "/" + path.substr(std::string(kAssetsPrefix).size());
}

}  // namespace tandem
