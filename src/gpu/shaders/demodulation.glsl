// Demodulation (passes/foveated/demodulation.h) on the GPU: illumination = (colour - emission) /
// albedo where there is a surface (depth > 0) with an albedo over 0.01, and back. The including
// kernel declares buffer reference Floats { float v[]; }.
vec3 demodAlbedo(uint64_t diffuse, uint64_t depth, bool enabled, uint i) {
  Floats d = Floats(diffuse);
  const bool on = enabled && Floats(depth).v[i] > 0.0;
  vec3 r;
  for (int k = 0; k < 3; ++k) {
    const float x = d.v[4u * i + uint(k)];  // DiffuseChannels: rgb, opacity
    r[k] = on && x > 0.01 ? min(x, 1.0) : 1.0;
  }
  return r;
}
vec3 demodEmitted(uint64_t emission, uint64_t depth, bool enabled, uint i) {
  Floats e = Floats(emission);
  return enabled && Floats(depth).v[i] > 0.0
             ? vec3(e.v[3u * i], e.v[3u * i + 1u], e.v[3u * i + 2u])
             : vec3(0.0);
}
