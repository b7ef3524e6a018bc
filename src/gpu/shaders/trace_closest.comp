#version 460
// The closest hit of each ray (RayTracer::intersect).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#define TRACE_KIND 0u
#include "trace.glsl"
