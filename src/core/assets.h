// Where third-party scenes live. Tandem's own scenes, tests and demo need none of them; the
// optional real-model scenes name their files as "$TANDEM_ASSETS/<folder>/<file>", so that one
// variable points them at a copy anywhere.
#pragma once
#include <string>

namespace tandem {

inline constexpr const char* kAssetsPrefix = "$TANDEM_ASSETS/";

// The TANDEM_ASSETS environment variable, or else ../shared/scenes beside the source tree.
std::string assetsDir();
// True when `path` starts with kAssetsPrefix.
bool isAssetPath(const std::string& path);
// `path` with a leading kAssetsPrefix replaced by assetsDir(); other paths unchanged.
std::string expandAssetPath(const std::string& path);

}  // namespace tandem
