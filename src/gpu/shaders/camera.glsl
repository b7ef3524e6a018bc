// Camera rays as Camera::generateRay makes them and primary_rays.h starts them (at the near
// plane, where the rasterizer clips).
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer CameraRef {
  GpuCamera c;
};

// The camera ray through pixel position p of the view (Camera::generateRay); tnear: where it
// starts.
void cameraRayAt(GpuCamera c, vec2 p, out vec3 origin, out vec3 dir, out float tnear) {
  const float sx = (p.x + c.jitter[0]) / float(c.width) * 2.0 - 1.0;
  const float sy = 1.0 - (p.y + c.jitter[1]) / float(c.height) * 2.0;
  const vec3 forward = vec3(c.forward[0], c.forward[1], c.forward[2]);
  const vec3 right = vec3(c.right[0], c.right[1], c.right[2]);
  const vec3 up = vec3(c.up[0], c.up[1], c.up[2]);
  if (c.orthographic == 0) {
    const float t = c.tanHalfFov;
    origin = vec3(c.eye[0], c.eye[1], c.eye[2]);
    dir = forward + right * (sx * t * c.aspect - c.lensSlope[0]) + up * (sy * t - c.lensSlope[1]);
    const float l2 = dot(dir, dir);
    dir = l2 > 0.0 ? dir / sqrt(l2) : vec3(0.0);
    tnear = c.nearPlane / max(dot(dir, forward), 1e-6);
  } else {
    const float hh = c.orthoHalfHeight;
    origin = vec3(c.position[0], c.position[1], c.position[2]) + right * (sx * hh * c.aspect) +
             up * (sy * hh);
    dir = forward;
    tnear = c.nearPlane;
  }
}

// The camera ray through pixel centre (x + 0.5, y + 0.5).
void cameraRay(GpuCamera c, int x, int y, out vec3 origin, out vec3 dir, out float tnear) {
  cameraRayAt(c, vec2(float(x) + 0.5, float(y) + 0.5), origin, dir, tnear);
}
