// The thin lens as Camera::lensPoint and generateThinLensRay make its rays: a point of the
// aperture (a disk by the concentric map, or a regular n-gon) and the ray from it through the
// pixel's point on the focus plane. Needs camera.glsl (and kPi).
struct ThinLensRays {
  float radius;    // of the aperture, metres (0: a pinhole)
  float focus;     // the focus distance along the view axis
  float rotation;  // of the polygon, radians
  int blades;      // 0: a disk; n >= 3: a regular n-gon
};

vec2 lensPoint(ThinLensRays L, float u1, float u2) {
  float lx = 0.0, ly = 0.0;
  if (L.blades >= 3) {
    const float n = float(L.blades), x = u1 * n;
    const float k = min(floor(x), n - 1.0), su = sqrt(u2), v = x - k;
    const float a0 = L.rotation + 2.0 * kPi * k / n, a1 = a0 + 2.0 * kPi / n;
    lx = su * ((1.0 - v) * cos(a0) + v * cos(a1));
    ly = su * ((1.0 - v) * sin(a0) + v * sin(a1));
  } else {
    const float p = 2.0 * u1 - 1.0, q = 2.0 * u2 - 1.0;
    float r = 0.0, phi = 0.0;
    if (p != 0.0 || q != 0.0) {
      if (abs(p) > abs(q)) {
        r = p;
        phi = kPi / 4.0 * (q / p);
      } else {
        r = q;
        phi = kPi / 2.0 - kPi / 4.0 * (p / q);
      }
    }
    lx = r * cos(phi);
    ly = r * sin(phi);
  }
  return vec2(L.radius * lx, L.radius * ly);
}

// The ray through pixel position p from aperture sample `lens` (two uniforms).
void thinLensRay(GpuCamera c, ThinLensRays L, vec2 p, vec2 lens, out vec3 o, out vec3 d) {
  float tnear;
  cameraRayAt(c, p, o, d, tnear);
  if (L.radius <= 0.0 || c.orthographic != 0) return;
  const vec2 l = lensPoint(L, lens.x, lens.y);
  const vec3 forward = vec3(c.forward[0], c.forward[1], c.forward[2]);
  const vec3 focus = o + d * (L.focus / dot(d, forward));
  o = vec3(c.eye[0], c.eye[1], c.eye[2]) + vec3(c.right[0], c.right[1], c.right[2]) * l.x +
      vec3(c.up[0], c.up[1], c.up[2]) * l.y;
  d = normalize(focus - o);
}
