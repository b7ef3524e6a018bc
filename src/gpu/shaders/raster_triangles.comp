#version 460
// raster_triangles: the compute rasterizer's set-up (raster_triangles.glsl), its depth planes
// solved in double as the CPU solves them.
#extension GL_GOOGLE_include_directive : require
#include "raster_triangles.glsl"
