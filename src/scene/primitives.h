// Procedural meshes: Walewski et al. 2019's plane, cube and UV sphere (slices x stacks), plus the
// shapes the built-in scenes are made of. All are unit-sized around the origin, with normals, UVs,
// tangents.
#pragma once
#include "scene/mesh.h"

namespace tandem {

Mesh makePlane(int subdivisions = 1);                   // XZ plane [-1,1]^2 facing +Y
Mesh makeCube();                                        // [-1,1]^3, faceted, 24 vertices
Mesh makeUvSphere(int slices = 32, int stacks = 16);    // radius 1
Mesh makeCylinder(int segments, int rings, bool caps);  // radius 1, y in [0,1]
// Half-ring arch in the XY plane: inner radius r0, outer r1, depth d (z in [-d/2, d/2]).
Mesh makeArch(float r0, float r1, float depth, int segments);
// A (p, q) torus knot tube (the trefoil for 2, 3): `segments` along the curve, `sides` around
// the tube of radius `tube`, scaled so that it fits [-1,1]^3 (the knot's ring in the XY plane).
// Tandem's own stand-in for a scanned statue: holes to see through, a silhouette that curves in
// every direction, self-shadowing and smooth normals.
Mesh makeTorusKnot(int p, int q, float tube, int segments, int sides);
// A hanging cloth: grid in XY (width w, height h, hanging down from y = 0) with sine folds.
Mesh makeCloth(float w, float h, int nx, int ny, float foldDepth, int folds);

}  // namespace tandem
