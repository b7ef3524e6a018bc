// The GPU's BVH layout and trace records (C++ and GLSL). Binary nodes of 32 bytes: an inner node
// (count 0) has its two children at `a` and a + 1; a leaf holds `count` items from `a` on
// (triangles in an object's BVH, objects in the BVH over them).
#ifndef TANDEM_GPU_BVH_H
#define TANDEM_GPU_BVH_H
#include "shared.h"
struct BvhNode {
  TD_FLOAT lox, loy, loz;
  TD_UINT a;
  TD_FLOAT hix, hiy, hiz;
  TD_UINT count;
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
  TD_UINT topRoot;  // the root of the BVH over the objects
  TD_UINT count;    // rays
};
#endif
