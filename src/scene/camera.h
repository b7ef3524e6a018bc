// Camera: perspective (vertical FoV) or orthographic, reversed-Z depth, sub-pixel jitter for
// TAA, and the thin-lens parameters of Tan et al. 2022 eq. 6 (the reference path tracer samples the
// lens; the DoF passes will use them too).
#pragma once
#include "core/math.h"

namespace tandem {

enum class Projection { Perspective, Orthographic };

struct CameraDesc {
  Projection projection = Projection::Perspective;
  Vec3 position{0, 1, 4};
  Vec3 lookAt{0, 1, 0};
  Vec3 up{0, 1, 0};
  float vfovDeg = 45.0f;          // perspective, in (0, 180)
  float orthoHeight = 2.0f;       // orthographic: world-space height of the view
  float nearPlane = 0.01f;        // > 0; reversed-Z with an infinite far plane for perspective
  float farPlane = 1000.0f;       // orthographic depth range only
  float apertureDiameter = 0.0f;  // thin lens (metres); 0 = pinhole
  float focalLength = 0.05f;      // metres
  float focusDistance = 5.0f;     // metres
  float sensorWidth = 0.036f;     // metres
  int apertureBlades = 0;         // 0 = circular aperture; n >= 3: regular n-gon (bokeh shape)
  float apertureRotationDeg = 0;  // rotation of the polygon about the view axis
};

// A stereo pair (Peres 2022): two eyes `ipd` metres apart along the camera's right axis, looking
// along parallel axes, or converged (toed in) on the point `convergence` metres ahead.
struct StereoDesc {
  bool enabled = false;
  float ipd = 0.064f;        // interpupillary distance, metres (> 0)
  bool converged = false;    // false: parallel axes
  float convergence = 2.0f;  // metres along the view axis where converged axes meet
};

// The camera of one eye: eye 0 is the left, 1 the right.
CameraDesc eyeCamera(const CameraDesc& centre, const StereoDesc& stereo, int eye);

// A camera evaluated for one frame at a given resolution.
struct Camera {
  CameraDesc desc;
  int width = 1, height = 1;
  Vec2 jitter{0, 0};  // sub-pixel offset in pixels, in [-0.5, 0.5]
  // Point of the lens this view looks through, in metres along right and up from the lens centre
  // (accumulated depth of field): the view moves there and the projection is sheared so the focus
  // plane (focusDistance ahead) projects where it does for the lens centre.
  Vec2 lens{0, 0};
  Vec3 eye;  // desc.position moved to the lens point
  Mat4 view, proj, viewProj, invView;
  Mat4 viewProjUnjittered;  // for motion vectors, which must not contain the jitter
  Vec3 forward, right, upVec;
  float tanHalfFov = 1, aspect = 1;  // cached for generateRay
  Vec2 lensSlope{0, 0};              // lens / focusDistance, cached for generateRay

  static Camera make(const CameraDesc& d, int width, int height, Vec2 jitter = {0, 0},
                     Vec2 lens = {0, 0});

  // Primary ray through pixel coordinate (px, py) (pixel centres at +0.5), jitter applied; from
  // the lens point through the focus-plane point of the pixel when `lens` is set.
  void generateRay(float px, float py, Vec3& origin, Vec3& dir) const;
  // The same ray with a direction not normalised (perspective: forward + offsets, so affine in
  // px and py; the raster resolve steps it across a row).
  void generateRayUnnormalized(float px, float py, Vec3& origin, Vec3& dir) const;
  // Thin-lens ray (Tan et al. 2022 §3.2.2): from a point of the aperture disk (diameter
  // apertureDiameter, picked by u1, u2 in [0,1)) through the point of the focus plane
  // (focusDistance along the view axis) that the pinhole ray of (px, py) meets. A point on the
  // focus plane stays sharp; one at depth z spreads over a disk of diameter
  // aperture |z - focus| / focus at that depth. Pinhole (and orthographic) when aperture is 0.
  // With apertureBlades = n >= 3 the lens point is uniform over the regular n-gon inscribed in
  // the aperture circle instead.
  void generateThinLensRay(float px, float py, float u1, float u2, Vec3& origin, Vec3& dir) const;
  // The lens point picked by (u1, u2) in [0,1)^2, in metres along right and up from the lens
  // centre: uniform over the aperture disk, or over its n-gon (the same map as the thin-lens
  // rays, so a lens point given to make() is one a thin-lens ray could start from).
  Vec2 lensPoint(float u1, float u2) const;
  // Reversed-Z depth of a world point: 1 at the near plane, -> 0 far away.
  float depthOf(Vec3 worldPos) const;
  // World point -> pixel coordinates (continuous); returns false behind the camera.
  bool project(Vec3 worldPos, Vec2& pixel) const;
};

}  // namespace tandem
