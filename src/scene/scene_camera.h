// The cameras a scene implies: its own (or one framing its bounds when it has none) and the
// camera along its recorded path (the one `bench` flies; a gentle orbit when it has none).
#pragma once
#include "scene/scene.h"

namespace tandem {

// The scene's camera, or one framing its bounds (like a model viewer) from the direction
// autoViewDirection picks; the near plane kept sensible for tiny models seen from close up.
CameraDesc defaultCamera(const Scene& s);
// Unit direction from the model's centre towards the automatic camera: front (+Z) and slightly
// above unless another view shows at least a quarter more of the model's surface (projected
// area of the faces turned towards it; both sides of double-sided faces).
Vec3 autoViewDirection(const Scene& s);
// The stereo pair for a scene without a camera of its own: the eyes no farther apart than 1/30
// of the distance to the model's nearest point (the stereographer's rule), so both eyes frame a
// model of any size as a viewer of small objects does. Unchanged when the scene has a camera or
// `ipdGiven` (the user chose the distance).
StereoDesc fitStereoToModel(const Scene& s, const CameraDesc& c, StereoDesc st, bool ipdGiven);
// Keeps the near plane below 5 % of the distance to the target.
void fitNearPlane(CameraDesc& c);
// The camera on the scene's path at path time t (seconds); `base` when the scene has no path.
CameraDesc pathCameraAt(const Scene& s, const CameraDesc& base, float t);
// Camera for frame i of n along the scene's path, or a gentle orbit of `base` when it has none.
CameraDesc pathCamera(const Scene& s, const CameraDesc& base, int i, int n);

}  // namespace tandem
