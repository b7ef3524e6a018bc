// The channels the heuristic hybrid's passes share: the secondary effects (the heuristic mask's
// and traced_mask's channels, rt_stats' per-effect counts) and the layout of ss_fallback's
// `fallback` buffer, written by ss_fallback and read by blend.
#pragma once
#include <string>
#include <vector>

#include "core/buffer.h"

namespace tandem {

// Secondary effects the hybrid pipeline can ray trace per object.
enum Effect : int { kShadow = 0, kReflection = 1, kRefraction = 2 };
constexpr int kEffectCount = 3;

// A buffer with a channel per effect (heuristic_mask, traced_mask, heuristic_order).
inline BufferSlot effectSlot(std::string slot, BufferKind kind, Extent extent = Extent::frame()) {
  return BufferSlot{std::move(slot), 0, kind, extent}.named({"shadow", "reflection", "refraction"});
}

// `fallback`: what stands in for an effect that was not traced.
namespace fallback {
constexpr int kReflection = 0;     // RGB: what the untraced mirror shows
constexpr int kRefraction = 3;     // RGB: what the untraced glass shows
constexpr int kShadow = 6;         // RGB: S of the untraced shadow (1: unshadowed)
constexpr int kCoversEffect = 9;   // 1 where reflection / refraction stand in
constexpr int kCoversShadow = 10;  // 1 where the shadow stands in
constexpr int kChannels = 11;
inline BufferSlot slot() {
  return BufferSlot{"fallback"}.named({"reflection_r", "reflection_g", "reflection_b",
                                       "refraction_r", "refraction_g", "refraction_b", "shadow_r",
                                       "shadow_g", "shadow_b", "covers_effect", "covers_shadow"});
}
}  // namespace fallback

}  // namespace tandem
