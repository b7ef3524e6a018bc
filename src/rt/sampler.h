// Low-discrepancy samples for the reference renderer: the Sobol (0,2)-sequence, Owen-scrambled
// with hashed nested uniform scrambling and padded per 2D dimension pair (Burley 2020,
// "Practical Hash-based Owen Scrambling"). Every pair of dimensions is a (0,2)-sequence of its
// own, so any power-of-two run of samples of a pixel is stratified in every elementary interval
// of every pair; the pairs are decorrelated by shuffling the sample index per pair. Deterministic
// for (seed, pixel, sample index): the same image whatever the thread or process count.
#pragma once
#include <cstdint>

#include "core/math.h"

namespace tandem {

constexpr uint32_t reverseBits32(uint32_t x) {
  x = __builtin_bswap32(x);  // bytes, then bits within bytes
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
}

// Owen scrambling of a 32-bit fixed-point value: each bit is flipped by a hash of the bits above
// it (the Laine-Karras permutation, applied to the reversed bits).
constexpr uint32_t laineKarras(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}
constexpr uint32_t nestedUniformScramble(uint32_t x, uint32_t seed) {
  return reverseBits32(laineKarras(reverseBits32(x), seed));
}

// The first two Sobol dimensions of index i as 32-bit fixed point (MSB = 1/2).
constexpr uint32_t sobolDim0(uint32_t i) {
  return reverseBits32(i);
}
uint32_t sobolDim1(uint32_t i);
constexpr uint32_t hashCombine(uint32_t seed, uint32_t v) {
  return seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2));
}
// The one per-frame seed: frame `frame` of a run seeded `seed` (the run's seed times the golden
// ratio, plus the frame times another odd constant: nearby seeds and frames land far apart, and
// the sampler hashes it further).
// Passes take it through FrameContext::frameSeed (the frame executed: a still shot's frames
// differ); references seed by the shot's frame number so a frame's truth does not depend on
// what was rendered before it.
constexpr uint64_t frameSeed(uint64_t seed, int64_t frame) {
  return seed * 0x9E3779B97F4A7C15ull + uint64_t(frame) * 0xD1B54A32D192ED03ull;
}

class SobolSampler {
 public:
  // pixelKey identifies the pixel (or any independent stream); index is the sample number.
  SobolSampler(uint64_t seed, uint64_t pixelKey, uint32_t index);
  Vec2 get2D();     // the next dimension pair, in [0,1)^2
  float uniform();  // a fresh pair's first coordinate (still stratified)

 private:
  // The next pair's shuffled index in the reversed-bit domain (the Laine-Karras output before
  // its final reversal), and the pair's seed. The sequence is the one the comment above defines;
  // it is computed where it needs the fewest bit reversals (the index is reversed once).
  uint32_t nextPair(uint32_t& pairSeed);
  uint32_t seed_, reversedIndex_, pair_ = 0;
};

}  // namespace tandem
