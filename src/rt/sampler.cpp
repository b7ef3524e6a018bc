#include "rt/sampler.h"

#include <array>

namespace tandem {

namespace {

// Sobol dimension 1 (primitive polynomial x + 1) has direction numbers v_k = v_{k-1} ^ v_{k-1}>>1,
// v_0 = 1/2. Its generator matrix is applied a byte at a time from tables (the bit loop's
// data-dependent branches mispredict on scrambled indices and cost more than the path).
constexpr std::array<std::array<uint32_t, 256>, 4> kSobol1Bytes = [] {
  std::array<uint32_t, 32> v{};
  v[0] = 1u << 31;
  for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
  std::array<std::array<uint32_t, 256>, 4> t{};
  for (int b = 0; b < 4; ++b)
    for (int x = 0; x < 256; ++x)
      for (int k = 0; k < 8; ++k)
        if (x & (1 << k)) t[b][x] ^= v[8 * b + k];
  return t;
}();

// The same map in the reversed-bit domain, y -> reverse(sobolDim1(reverse(y))): still linear, so
// still four byte tables. The scramblers work on reversed bits, so the index never needs turning
// back before dimension 1 is looked up.
constexpr std::array<std::array<uint32_t, 256>, 4> kSobol1ReversedBytes = [] {
  std::array<std::array<uint32_t, 256>, 4> t{};
  for (int b = 0; b < 4; ++b)
    for (int x = 0; x < 256; ++x) {
      const uint32_t i = reverseBits32(uint32_t(x) << (8 * b));
      uint32_t d = 0;
      for (int k = 0; k < 4; ++k) d ^= kSobol1Bytes[size_t(k)][(i >> (8 * k)) & 255u];
      t[size_t(b)][size_t(x)] = reverseBits32(d);
    }
  return t;
}();

uint32_t sobolDim1Reversed(uint32_t y) {
  return kSobol1ReversedBytes[0][y & 255u] ^ kSobol1ReversedBytes[1][(y >> 8) & 255u] ^
         kSobol1ReversedBytes[2][(y >> 16) & 255u] ^ kSobol1ReversedBytes[3][y >> 24];
}

// A 64 -> 32 bit mix (splitmix64 finaliser) to seed each pixel's stream.
uint32_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return uint32_t((z ^ (z >> 31)) >> 16);
}

float toUnit(uint32_t x) {
  return float(x >> 8) * (1.0f / 16777216.0f);
}

}  // namespace

uint32_t sobolDim1(uint32_t i) {
  return kSobol1Bytes[0][i & 255u] ^ kSobol1Bytes[1][(i >> 8) & 255u] ^
         kSobol1Bytes[2][(i >> 16) & 255u] ^ kSobol1Bytes[3][i >> 24];
}

SobolSampler::SobolSampler(uint64_t seed, uint64_t pixelKey, uint32_t index)
    : seed_(mix64(seed * 0x9E3779B97F4A7C15ull ^ mix64(pixelKey + 0x632BE59BD9B4E019ull))),
      reversedIndex_(reverseBits32(index)) {}

// Each pair gets its own seed and its own shuffle of the sample index. The shuffle is itself an
// Owen scramble, so every aligned power-of-two block of indices maps to a permuted block:
// stratification survives while the pairs decorrelate.
// nestedUniformScramble(index, .) without its final reversal.
uint32_t SobolSampler::nextPair(uint32_t& pairSeed) {
  pairSeed = hashCombine(seed_, pair_++);
  return laineKarras(reversedIndex_, hashCombine(pairSeed, 0x68bc21ebu));
}

// With i = reverse(y) the shuffled index: dimension 0 is nestedUniformScramble(sobolDim0(i)) =
// reverse(laineKarras(i)), dimension 1 nestedUniformScramble(sobolDim1(i)) =
// reverse(laineKarras(sobolDim1Reversed(y))).
float SobolSampler::uniform() {
  uint32_t s;
  const uint32_t y = nextPair(s);
  return toUnit(reverseBits32(laineKarras(reverseBits32(y), hashCombine(s, 0x02e5be93u))));
}

Vec2 SobolSampler::get2D() {
  uint32_t s;
  const uint32_t y = nextPair(s);
  return {toUnit(reverseBits32(laineKarras(reverseBits32(y), hashCombine(s, 0x02e5be93u)))),
          toUnit(reverseBits32(laineKarras(sobolDim1Reversed(y), hashCombine(s, 0x967a889bu))))};
}

}  // namespace tandem
