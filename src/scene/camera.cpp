#include "scene/camera.h"

#include <cmath>

namespace tandem {

CameraDesc eyeCamera(const CameraDesc& centre, const StereoDesc& stereo, int eye) {
  if (!stereo.enabled) return centre;
  const Mat4 view = Mat4::lookAt(centre.position, centre.lookAt, centre.up);
  const Vec3 right(view.m[0][0], view.m[0][1], view.m[0][2]);
  const Vec3 forward = -Vec3(view.m[2][0], view.m[2][1], view.m[2][2]);
  const Vec3 offset = right * ((eye == 0 ? -0.5f : 0.5f) * stereo.ipd);
  CameraDesc d = centre;
  d.position = centre.position + offset;
  // Parallel: the target moves with the eye. Converged: both eyes aim at the same point.
  d.lookAt =
      stereo.converged ? centre.position + forward * stereo.convergence : centre.lookAt + offset;
  return d;
}

Camera Camera::make(const CameraDesc& d, int width, int height, Vec2 jitter, Vec2 lens) {
  Camera c;
  c.desc = d;
  c.width = width;
  c.height = height;
  c.jitter = jitter;
  const Mat4 centreView = Mat4::lookAt(d.position, d.lookAt, d.up);
  c.right = Vec3(centreView.m[0][0], centreView.m[0][1], centreView.m[0][2]);
  c.upVec = Vec3(centreView.m[1][0], centreView.m[1][1], centreView.m[1][2]);
  c.forward = -Vec3(centreView.m[2][0], centreView.m[2][1], centreView.m[2][2]);
  if (d.projection != Projection::Perspective) lens = {0, 0};
  c.lens = lens;
  c.lensSlope = {lens.x / d.focusDistance, lens.y / d.focusDistance};
  const Vec3 shift = c.right * lens.x + c.upVec * lens.y;
  c.eye = d.position + shift;
  c.view = lens.x == 0 && lens.y == 0 ? centreView : Mat4::lookAt(c.eye, d.lookAt + shift, d.up);
  c.invView = c.view.inverse();
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
    // Shear for a lens point: a point of the focus plane (view z = -focus) keeps its NDC.
    p.m[0][2] = -p.m[0][0] * lens.x / d.focusDistance;
    p.m[1][2] = -p.m[1][1] * lens.y / d.focusDistance;
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
  generateRayUnnormalized(px, py, origin, dir);
  if (desc.projection == Projection::Perspective) dir = normalize(dir);
}

void Camera::generateRayUnnormalized(float px, float py, Vec3& origin, Vec3& dir) const {
  float sx = (px + jitter.x) / width * 2.0f - 1.0f;   // NDC x
  float sy = 1.0f - (py + jitter.y) / height * 2.0f;  // NDC y
  if (desc.projection == Projection::Perspective) {
    float t = tanHalfFov;
    origin = eye;
    // Through the pixel's point of the focus plane (lens 0: the pinhole ray).
    dir = forward + right * (sx * t * aspect - lensSlope.x) + upVec * (sy * t - lensSlope.y);
  } else {
    float hh = desc.orthoHeight * 0.5f;
    origin = desc.position + right * (sx * hh * aspect) + upVec * (sy * hh);
    dir = forward;
  }
}

Vec2 Camera::lensPoint(float u1, float u2) const {
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
  return {radius * lx, radius * ly};
}

void Camera::generateThinLensRay(float px, float py, float u1, float u2, Vec3& origin,
                                 Vec3& dir) const {
  generateRay(px, py, origin, dir);
  if (desc.apertureDiameter <= 0.0f || desc.projection != Projection::Perspective) return;
  const Vec2 l = lensPoint(u1, u2);
  Vec3 focus = origin + dir * (desc.focusDistance / dot(dir, forward));
  origin = eye + right * l.x + upVec * l.y;
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
