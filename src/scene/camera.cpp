#include "scene/camera.h"

#include <cmath>

namespace tandem {

Camera Camera::make(const CameraDesc& d, int width, int height, Vec2 jitter) {
  Camera c;
  c.desc = d;
  c.width = width;
  c.height = height;
  c.jitter = jitter;
  c.view = Mat4::lookAt(d.position, d.lookAt, d.up);
  c.invView = c.view.inverse();
  c.right = Vec3(c.view.m[0][0], c.view.m[0][1], c.view.m[0][2]);
  c.upVec = Vec3(c.view.m[1][0], c.view.m[1][1], c.view.m[1][2]);
  c.forward = -Vec3(c.view.m[2][0], c.view.m[2][1], c.view.m[2][2]);
  float aspect = float(width) / float(height);
  c.aspect = aspect;
  c.tanHalfFov = std::tan(radians(d.vfovDeg) * 0.5f);
  Mat4 p;
  if (d.projection == Projection::Perspective) {
    // Reversed-Z, infinite far: clip = (x*f/a, y*f, near, -z_view); ndc z = near / z_dist.
    float f = 1.0f / std::tan(radians(d.vfovDeg) * 0.5f);
    p.m[0][0] = f / aspect;
    p.m[1][1] = f;
    p.m[2][2] = 0;
    p.m[2][3] = d.nearPlane;
    p.m[3][2] = -1;
    p.m[3][3] = 0;
  } else {
    // Reversed-Z orthographic: ndc z = (far - dist) / (far - near).
    float hh = d.orthoHeight * 0.5f, hw = hh * aspect;
    float range = d.farPlane - d.nearPlane;
    p.m[0][0] = 1.0f / hw;
    p.m[1][1] = 1.0f / hh;
    p.m[2][2] = 1.0f / range;
    p.m[2][3] = d.farPlane / range;
  }
  // Jitter moves each pixel's sample point to centre + jitter; the image therefore shifts by
  // -jitter in NDC (x right, y up; pixel y grows downwards).
  Mat4 j = Mat4::translate({-2.0f * jitter.x / width, 2.0f * jitter.y / height, 0});
  c.viewProjUnjittered = p * c.view;
  c.proj = j * p;
  c.viewProj = c.proj * c.view;
  return c;
}

void Camera::generateRay(float px, float py, Vec3& origin, Vec3& dir) const {
  float sx = (px + jitter.x) / width * 2.0f - 1.0f;   // NDC x
  float sy = 1.0f - (py + jitter.y) / height * 2.0f;  // NDC y
  if (desc.projection == Projection::Perspective) {
    float t = tanHalfFov;
    origin = desc.position;
    dir = normalize(forward + right * (sx * t * aspect) + upVec * (sy * t));
  } else {
    float hh = desc.orthoHeight * 0.5f;
    origin = desc.position + right * (sx * hh * aspect) + upVec * (sy * hh);
    dir = forward;
  }
}

void Camera::generateThinLensRay(float px, float py, float u1, float u2, Vec3& origin,
                                 Vec3& dir) const {
  generateRay(px, py, origin, dir);
  if (desc.apertureDiameter <= 0.0f || desc.projection != Projection::Perspective) return;
  const float radius = 0.5f * desc.apertureDiameter;
  float lx = 0.0f, ly = 0.0f;  // lens point in units of the aperture radius
  if (desc.apertureBlades >= 3) {
    // Regular n-gon as a fan of n equal triangles: u1 picks one and is reused inside it.
    const float n = float(desc.apertureBlades), x = u1 * n;
    const float k = std::min(std::floor(x), n - 1.0f), su = std::sqrt(u2), v = x - k;
    const float a0 = radians(desc.apertureRotationDeg) + 2.0f * kPi * k / n;
    const float a1 = a0 + 2.0f * kPi / n;
    // Uniform point in triangle (centre, corner a0, corner a1).
    lx = su * ((1.0f - v) * std::cos(a0) + v * std::cos(a1));
    ly = su * ((1.0f - v) * std::sin(a0) + v * std::sin(a1));
  } else {
    // Concentric square-to-disk map (Shirley & Chiu 1997): uniform over the aperture.
    float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f, r = 0.0f, phi = 0.0f;
    if (a != 0.0f || b != 0.0f) {
      if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = kPi / 4.0f * (b / a);
      } else {
        r = b;
        phi = kPi / 2.0f - kPi / 4.0f * (a / b);
      }
    }
    lx = r * std::cos(phi);
    ly = r * std::sin(phi);
  }
  Vec3 focus = origin + dir * (desc.focusDistance / dot(dir, forward));
  origin = desc.position + right * (radius * lx) + upVec * (radius * ly);
  dir = normalize(focus - origin);
}

float Camera::depthOf(Vec3 p) const {
  float dist = dot(p - desc.position, forward);
  if (desc.projection == Projection::Perspective) return dist > 0 ? desc.nearPlane / dist : 0.0f;
  return (desc.farPlane - dist) / (desc.farPlane - desc.nearPlane);
}

bool Camera::project(Vec3 p, Vec2& pixel) const {
  Vec4 c = viewProj * Vec4(p, 1.0f);
  if (desc.projection == Projection::Perspective && c.w <= 1e-8f) return false;
  float iw = 1.0f / c.w;
  pixel = {(c.x * iw * 0.5f + 0.5f) * width, (0.5f - c.y * iw * 0.5f) * height};
  return true;
}

}  // namespace tandem
