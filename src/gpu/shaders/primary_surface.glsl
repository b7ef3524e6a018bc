// PrimarySurfaces (passes/foveated/primary_surface.h) on the GPU: a pixel's primary surface as
// the foveated path tracer and direct_light read it from the G-buffer, the sky test and the
// direction to the viewer. Needs scene.glsl (Surface) and foveated_args.h.
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer GFloats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer FoveatedViews {
  FoveatedView v[];
};

vec3 gbuffer3(uint64_t target, uint i) {
  GFloats t = GFloats(target);
  return vec3(t.v[3u * i], t.v[3u * i + 1u], t.v[3u * i + 2u]);
}
bool gbufferSky(GpuPrimarySurfaces g, uint i) { return GFloats(g.depth).v[i] <= 0.0; }
Surface gbufferSurface(GpuPrimarySurfaces g, uint i) {
  Surface s;
  s.position = gbuffer3(g.position, i);
  s.normal = gbuffer3(g.normal, i);
  s.geoNormal = gbuffer3(g.geoNormal, i);
  s.uv = vec2(0.0);
  s.emission = gbuffer3(g.emission, i);
  s.ambient = vec3(0.0);
  GFloats d = GFloats(g.diffuse);  // DiffuseChannels: rgb, opacity
  s.diffuse = vec3(d.v[4u * i], d.v[4u * i + 1u], d.v[4u * i + 2u]);
  s.diffuseOpacity = d.v[4u * i + 3u];
  s.specular = vec3(0.0);
  s.specularExponent = 0.0, s.reflectivity = 0.0, s.ior = 1.0, s.opacity = 1.0;
  s.object = -1, s.material = -1;
  s.t = 0.0;
  return s;
}
// PrimarySurfaces::towardsViewer.
vec3 towardsViewer(FoveatedView v, vec3 p) {
  return v.orthographic == 0 ? safeNormalize(v3(v.eye) - p) : -v3(v.forward);
}
