// Listing 8a's shadow term S of a G-buffer surface (Walewski et al. 2019), as classifiedShadowTile
// computes it: each light whose share of the surface's light reaches the cull floor is asked
// about — by a shadow ray, by the shadow maps' classification with rays for the undecided, or by
// the maps' lookups alone (the shadow mode in TD_WHITTED_CLASSIFIED / _MAPS of whitted.flags) —
// and S = 1 - the light the occluders block. The including kernel includes scene.glsl,
// shadow_maps.glsl and whitted.glsl first.

// S at s seen along wo, given `total` = shadeUnshadowed(s, wo) (the light the cull floor is a share
// of; deferred shading has it already). `classLight` >= 0: `shares` covers that light alone, else
// every light: the (traced, lit, shadowed) shares of the lights that reach s (rt_secondary's
// shadow_class).
vec3 shadowTermOf(Surface s, vec3 wo, vec3 total, int classLight, out vec3 shares) {
  Lights lights = Lights(S.lights);
  const float floorShare = whitted.shadowCull * luminance(total);
  const bool classified = (whitted.flags & TD_WHITTED_CLASSIFIED) != 0u;
  const bool mapsOnly = (whitted.flags & TD_WHITTED_MAPS) != 0u;
  vec3 blocked = vec3(0.0), classes = vec3(0.0);
  float reached = 0.0;
  for (uint i = 0u; i < S.lightCount; ++i) {
    const GpuLight l = lights.l[i];
    const vec3 term = lightTerm(s, wo, l);
    const float share = luminance(term);
    const bool asked = l.castsShadows != 0u && share > 0.0 && share >= floorShare;
    int c = asked ? TD_SHADOW_TRACED : TD_SHADOW_CULLED;
    vec3 vis = vec3(1.0);
    if (asked && classified) c = shadowClassify(i, s.position, s.geoNormal, s.object);
    if (asked && mapsOnly) {
      const float v = shadowVisibility(i, s.position, s.geoNormal);
      vis = vec3(v);
      c = v > 0.5 ? TD_SHADOW_LIT : TD_SHADOW_SHADOWED;
    } else if (c == TD_SHADOW_SHADOWED) {
      vis = vec3(0.0);
    }
    if (c == TD_SHADOW_TRACED) {
      ++rays;
      vec3 wi, radiance;
      float dist;
      sampleLight(l, s.position, wi, dist, radiance);
      const float tfar = isinf(dist) ? kInf : dist * (1.0 - 1e-4);
      vis = transmittance(offsetRayOrigin(s, wi), wi, tfar,
                          (whitted.flags & TD_WHITTED_TEXTURED_SHADOWS) != 0u);
    }
    culled += c == TD_SHADOW_CULLED ? 1u : 0u;
    traced += c == TD_SHADOW_TRACED ? 1u : 0u;
    shadowLit += c == TD_SHADOW_LIT ? 1u : 0u;
    shadowShadowed += c == TD_SHADOW_SHADOWED ? 1u : 0u;
    if (c != TD_SHADOW_CULLED && (classLight < 0 || uint(classLight) == i)) {
      reached += 1.0;
      classes += vec3(c == TD_SHADOW_TRACED ? 1.0 : 0.0, c == TD_SHADOW_LIT ? 1.0 : 0.0,
                      c == TD_SHADOW_SHADOWED ? 1.0 : 0.0);
    }
    blocked += term * (vec3(1.0) - vis);
  }
  shares = reached > 0.0 ? classes / reached : classes;
  return vec3(1.0) - blocked;
}

// S at s seen along wo, its unshadowed light summed here.
vec3 shadowTerm(Surface s, vec3 wo, int classLight, out vec3 shares) {
  return shadowTermOf(s, wo, shadeUnshadowed(s, wo), classLight, shares);
}
