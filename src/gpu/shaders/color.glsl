// luminance (core/math.h): Rec. 709 weights, the one definition every kernel includes.
#ifndef TANDEM_GPU_COLOR_GLSL
#define TANDEM_GPU_COLOR_GLSL
float luminance(vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
#endif
