// SobolSampler (rt/sampler.cpp) bit for bit: Owen-scrambled Sobol points of a pixel's sample,
// two dimensions a pair. Needs GL_EXT_shader_explicit_arithmetic_types_int64.
uint laineKarras(uint x, uint seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}
uint hashCombine(uint seed, uint v) { return seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2)); }
uint sobolDim1(uint i) {  // direction numbers v_k = v_{k-1} ^ v_{k-1} >> 1, v_0 = 1/2
  uint v = 1u << 31, r = 0u;
  for (int k = 0; k < 32; ++k, v ^= v >> 1)
    if (((i >> k) & 1u) != 0u) r ^= v;
  return r;
}
uint mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ul;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebul;
  return uint((z ^ (z >> 31)) >> 16);
}
float toUnit(uint x) { return float(x >> 8) * (1.0 / 16777216.0); }

uint samplerSeed, samplerIndex, samplerPair;
void startSampler(uint64_t seed, uint64_t pixel, uint index) {
  samplerSeed = mix64(seed * 0x9E3779B97F4A7C15ul ^ uint64_t(mix64(pixel + 0x632BE59BD9B4E019ul)));
  samplerIndex = bitfieldReverse(index);
  samplerPair = 0u;
}
uint nextPair(out uint pairSeed) {
  pairSeed = hashCombine(samplerSeed, samplerPair++);
  return laineKarras(samplerIndex, hashCombine(pairSeed, 0x68bc21ebu));
}
float uniform1() {
  uint s;
  const uint y = nextPair(s);
  return toUnit(bitfieldReverse(laineKarras(bitfieldReverse(y), hashCombine(s, 0x02e5be93u))));
}
vec2 uniform2() {
  uint s;
  const uint y = nextPair(s);
  const uint d1 = bitfieldReverse(sobolDim1(bitfieldReverse(y)));
  return vec2(toUnit(bitfieldReverse(laineKarras(bitfieldReverse(y), hashCombine(s, 0x02e5be93u)))),
              toUnit(bitfieldReverse(laineKarras(d1, hashCombine(s, 0x967a889bu)))));
}
