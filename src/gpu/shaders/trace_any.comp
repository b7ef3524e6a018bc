#version 460
// Whether anything lies between each ray's tnear and tfar (RayTracer::occluded, opaque
// geometry): the first hit found ends the ray.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#define TRACE_KIND TRACE_ANY
#include "trace.glsl"
