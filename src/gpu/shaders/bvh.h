// The GPU's BVH layout and trace records (C++ and GLSL). Binary nodes of 32 bytes: an inner node
// (count 0) has its two children at `a` and a + 1; a leaf holds `count` items from `a` on
// (triangles in an object's BVH, objects in the BVH over them). An object that moves while the
// shutter is open keeps its triangles at every time step (ObjectMotion) and its boxes bound them
// all; a ray meets it where it is at the ray's shutter fraction, linear between steps, as Embree
// interpolates a geometry's time steps.
#ifndef TANDEM_GPU_BVH_H
#define TANDEM_GPU_BVH_H
#include "shared.h"
struct BvhNode {
  TD_FLOAT lox, loy, loz;
  TD_UINT a;
  TD_FLOAT hix, hiy, hiz;
  TD_UINT count;
};
// Per object: `steps` time steps (0: it stands still), its first triangle in the leaf order of
// TraceArgs::triangles, and where its steps start in TraceArgs::motionTriangles (in triangles of
// 9 floats; triangle i's step s at first + i * steps + s).
struct ObjectMotion {
  TD_UINT steps, firstTriangle, firstStep, pad;
};
struct GpuRay {
  TD_FLOAT ox, oy, oz, tnear;
  TD_FLOAT dx, dy, dz, tfar;
};
struct GpuHit {  // object -1: no hit
  TD_FLOAT t, u, v;
  TD_INT object, prim;
  TD_UINT pad0, pad1, pad2;
};
struct TraceArgs {
  TD_ADDR nodes;         // every object's BVH, then the one over the objects
  TD_ADDR triangles;     // 9 floats a triangle (v0, v1, v2, world space), in leaf order
  TD_ADDR trianglePrim;  // the triangle's index in its object
  TD_ADDR objectRoot;    // per object its BVH's root node, then the top leaves' object ids
  TD_ADDR rays;
  TD_ADDR hits;
  TD_UINT topRoot;          // the root of the BVH over the objects
  TD_UINT count;            // rays
  TD_ADDR objectMotion;     // ObjectMotion per object
  TD_ADDR motionTriangles;  // the moving objects' triangles at each time step
};
#endif
