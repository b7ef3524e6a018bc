#version 460
// raster_triangles on a device without 64-bit floats: the depth planes solved in float.
#extension GL_GOOGLE_include_directive : require
#define TD_SETUP_FLOAT
#include "raster_triangles.glsl"
