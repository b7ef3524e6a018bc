// The camera's thin lens as the depth-of-field passes see it (Tan et al. 2022 §3.3, eq. 6): the
// signed circle of confusion (CoC) of a point in pixels, and the zone of focus. One lens for every
// pass: the CoC here is exactly the spread of Camera::generateThinLensRay's rays (the reference
// renderer's and rt_dof's), because it is derived from the same aperture, focus distance and
// projection. Eq. 6 writes the sensor term as a·f / ((d − f)·w_s / w_i); for a sensor that fills
// the camera's field of view (the thin-lens equation puts it f·d / (d − f) behind the lens),
// that term is a·P / d with P = w_i / (2 tan(fov / 2)) pixels per unit of slope, which is what
// is used here: focalLength and sensorWidth only matter through the field of view they imply.
#pragma once
#include <cmath>
#include <limits>

#include "scene/camera.h"

namespace tandem {

struct ThinLens {
  float aperture = 0;        // diameter, metres
  float focus = 1;           // focus distance d, metres along the view axis
  float pixelsPerSlope = 1;  // P: pixels per unit of tan(angle) off the view axis
  int blades = 0;            // 0: circular; n >= 3: regular n-gon
  float rotationDeg = 0;     // of the polygon, about the view axis

  static ThinLens of(const Camera& c) {
    ThinLens l;
    if (c.desc.projection == Projection::Perspective) l.aperture = c.desc.apertureDiameter;
    l.focus = c.desc.focusDistance;
    l.pixelsPerSlope = float(c.height) / (2.0f * c.tanHalfFov);
    l.blades = c.desc.apertureBlades;
    l.rotationDeg = c.desc.apertureRotationDeg;
    return l;
  }
  bool active() const { return aperture > 0; }
  // Signed CoC diameter in pixels of a point at view depth z (metres along the view axis):
  // > 0 behind the focus plane (far field), < 0 in front (near field). z = infinity (the sky)
  // gives the far-field limit a·P / d.
  float coc(float z) const {
    if (!(z < std::numeric_limits<float>::infinity())) return aperture * pixelsPerSlope / focus;
    return aperture * pixelsPerSlope * (z - focus) / (std::max(z, 1e-6f) * focus);
  }
  // Eq. 6: the depths whose |CoC| is at most maxCoc pixels (√2 in the paper). zFar is infinite
  // when even the sky is that sharp.
  void zoneOfFocus(float maxCoc, float& zNear, float& zFar) const {
    const float k = aperture * pixelsPerSlope;  // a·f·w_i / ((d − f)·w_s) · d in eq. 6's terms
    zNear = k * focus / (k + maxCoc * focus);
    const float den = k - maxCoc * focus;
    zFar = den > 0 ? k * focus / den : std::numeric_limits<float>::infinity();
  }
};

}  // namespace tandem
