// Writing and reading the G-buffer's targets (raster/gbuffer.h GBufferView::write and
// writeBackground, shading/gbuffer_sample.h GBufferReader::read), and motion vectors
// (motionVector, backgroundMotion).
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Target { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer TargetsRef {
  GBufferTargets g;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer ViewRef { GpuView v; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer MotionRef {
  GpuObjectMotion m[];
};

void put3(uint64_t target, uint i, vec3 v) {
  Target t = Target(target);
  t.v[3u * i] = v.x;
  t.v[3u * i + 1u] = v.y;
  t.v[3u * i + 2u] = v.z;
}
void put4(uint64_t target, uint i, vec3 v, float w) {
  Target t = Target(target);
  t.v[4u * i] = v.x;
  t.v[4u * i + 1u] = v.y;
  t.v[4u * i + 2u] = v.z;
  t.v[4u * i + 3u] = w;
}
vec3 get3(uint64_t target, uint i) {
  Target t = Target(target);
  return vec3(t.v[3u * i], t.v[3u * i + 1u], t.v[3u * i + 2u]);
}
vec4 get4(uint64_t target, uint i) {
  Target t = Target(target);
  return vec4(t.v[4u * i], t.v[4u * i + 1u], t.v[4u * i + 2u], t.v[4u * i + 3u]);
}

// Each target is written where its address is non-zero (vbuffer_shading writes only what is read).
void writeSurface(GBufferTargets g, uint i, Surface s, float depth, vec2 motion) {
  if (g.depth != 0ul) Target(g.depth).v[i] = depth;
  if (g.position != 0ul) put3(g.position, i, s.position);
  if (g.normal != 0ul) put3(g.normal, i, s.normal);
  if (g.geoNormal != 0ul) put3(g.geoNormal, i, s.geoNormal);
  if (g.diffuse != 0ul) put4(g.diffuse, i, s.diffuse, s.diffuseOpacity);
  if (g.specular != 0ul) put4(g.specular, i, s.specular, s.specularExponent);
  if (g.emission != 0ul) put3(g.emission, i, s.emission);
  if (g.ambient != 0ul) put3(g.ambient, i, s.ambient);
  if (g.optical != 0ul) put3(g.optical, i, vec3(s.reflectivity, s.ior, s.opacity));
  if (g.objectId != 0ul) Target(g.objectId).v[i] = float(s.object);
  if (g.materialId != 0ul) Target(g.materialId).v[i] = float(s.material);
  if (g.motion != 0ul) Target(g.motion).v[2u * i] = motion.x, Target(g.motion).v[2u * i + 1u] = motion.y;
}

void writeBackground(GBufferTargets g, uint i, vec2 motion) {
  if (g.depth != 0ul) Target(g.depth).v[i] = 0.0;
  if (g.position != 0ul) put3(g.position, i, vec3(0.0));
  if (g.normal != 0ul) put3(g.normal, i, vec3(0.0));
  if (g.geoNormal != 0ul) put3(g.geoNormal, i, vec3(0.0));
  if (g.diffuse != 0ul) put4(g.diffuse, i, vec3(0.0), 0.0);
  if (g.specular != 0ul) put4(g.specular, i, vec3(0.0), 0.0);
  if (g.emission != 0ul) put3(g.emission, i, vec3(0.0));
  if (g.ambient != 0ul) put3(g.ambient, i, vec3(0.0));
  if (g.optical != 0ul) put3(g.optical, i, vec3(0.0));
  if (g.objectId != 0ul) Target(g.objectId).v[i] = -1.0;
  if (g.materialId != 0ul) Target(g.materialId).v[i] = -1.0;
  if (g.motion != 0ul) Target(g.motion).v[2u * i] = motion.x, Target(g.motion).v[2u * i + 1u] = motion.y;
}

// GBufferReader::read: false for background.
bool readSurface(GBufferTargets g, uint i, out Surface s) {
  const float object = Target(g.objectId).v[i];
  if (object < 0.0) return false;
  s.position = get3(g.position, i);
  s.normal = get3(g.normal, i);
  s.geoNormal = get3(g.geoNormal, i);
  const vec4 d = get4(g.diffuse, i), sp = get4(g.specular, i);
  s.diffuse = d.xyz;
  s.diffuseOpacity = d.w;
  s.specular = sp.xyz;
  s.specularExponent = sp.w;
  s.emission = get3(g.emission, i);
  s.ambient = get3(g.ambient, i);
  const vec3 o = get3(g.optical, i);
  s.reflectivity = o.x;
  s.ior = o.y;
  s.opacity = o.z;
  s.object = int(object);
  s.material = int(Target(g.materialId).v[i]);
  s.uv = vec2(0.0);
  s.t = 0.0;
  return true;
}

// projectToPixel: homogeneous point -> pixel coordinates through the row-major vp; false behind
// the camera.
bool projectToPixel(float vp[16], GpuCamera c, vec4 q, out vec2 px) {
  const vec4 h = vec4(vp[0] * q.x + vp[1] * q.y + vp[2] * q.z + vp[3] * q.w,
                      vp[4] * q.x + vp[5] * q.y + vp[6] * q.z + vp[7] * q.w,
                      vp[8] * q.x + vp[9] * q.y + vp[10] * q.z + vp[11] * q.w,
                      vp[12] * q.x + vp[13] * q.y + vp[14] * q.z + vp[15] * q.w);
  px = vec2(0.0);
  if (h.w <= 1e-8) return false;
  px = vec2((h.x / h.w * 0.5 + 0.5) * float(c.width), (0.5 - h.y / h.w * 0.5) * float(c.height));
  return true;
}

vec2 screenMotion(GpuView v, vec4 now, vec4 before) {
  vec2 a, b;
  if (!projectToPixel(v.viewProj, v.camera, now, a) ||
      !projectToPixel(v.prevViewProj, v.camera, before, b))
    return vec2(0.0);
  return a - b;
}

// Where the point p of an object was last frame (itself unless the object moved).
vec3 previousPosition(GpuObjectMotion m, vec3 p) {
  if (m.moved == 0u) return p;
  const float w[12] = m.worldToPrev;
  return vec3(w[0] * p.x + w[1] * p.y + w[2] * p.z + w[3],
              w[4] * p.x + w[5] * p.y + w[6] * p.z + w[7],
              w[8] * p.x + w[9] * p.y + w[10] * p.z + w[11]);
}

vec2 motionVector(GpuView v, uint64_t motion, int object, vec3 p) {
  const GpuObjectMotion m = MotionRef(motion).m[object];
  if (m.moved == 0u && v.cameraMoved == 0) return vec2(0.0);
  return screenMotion(v, vec4(p, 1.0), vec4(previousPosition(m, p), 1.0));
}

// motionVectorAtPixel: a point on the camera ray through view-local pixel centre `pixel` is seen
// now at pixel + jitter by the unjittered camera; only where it was needs a projection.
vec2 motionAtPixel(GpuView v, uint64_t motion, int object, vec3 p, vec2 pixel) {
  const GpuObjectMotion m = MotionRef(motion).m[object];
  if (m.moved == 0u && v.cameraMoved == 0) return vec2(0.0);
  vec2 before;
  if (!projectToPixel(v.prevViewProj, v.camera, vec4(previousPosition(m, p), 1.0), before))
    return vec2(0.0);
  return pixel + vec2(v.camera.jitter[0], v.camera.jitter[1]) - before;
}

vec2 backgroundMotion(GpuView v, vec3 dir) {
  if (v.cameraMoved == 0 || v.perspective == 0) return vec2(0.0);
  return screenMotion(v, vec4(dir, 0.0), vec4(dir, 0.0));
}

// Camera::depthOf (reversed Z).
float depthOf(GpuView v, vec3 p) {
  const vec3 forward = vec3(v.camera.forward[0], v.camera.forward[1], v.camera.forward[2]);
  const float dist = dot(p - vec3(v.depthOrigin[0], v.depthOrigin[1], v.depthOrigin[2]), forward);
  if (v.perspective != 0) return dist > 0.0 ? v.camera.nearPlane / dist : 0.0;
  return (v.farPlane - dist) / (v.farPlane - v.camera.nearPlane);
}
