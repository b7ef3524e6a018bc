// Arguments of the depth-of-field kernels (C++ and GLSL; Tan et al. 2022): dof_coc.comp (the
// circle of confusion), postfx_dof.comp (the post-process gather, one stage a dispatch) and
// dof_composite.comp (eq. 7). Buffers are the CPU passes' (passes/dof/dof_common.h).
#ifndef TANDEM_GPU_DOF_ARGS_H
#define TANDEM_GPU_DOF_ARGS_H
#include "shared.h"

// The thin lens (scene/thin_lens.h) and one view's eye.
struct DofCocArgs {
  TD_ADDR position, depth, coc;
  TD_FLOAT eyeX, eyeY, eyeZ, forwardX, forwardY, forwardZ;
  TD_FLOAT aperture, focus, pixelsPerSlope, pad;
  TD_UINT frameWidth, viewX, viewY, width, height, lensActive;
};

// postfx_dof's stages, in order (PostfxDofPass's steps 1-5).
#define TD_POSTFX_DOWNSAMPLE 0u
#define TD_POSTFX_TILE_MAX 1u
#define TD_POSTFX_NEIGHBOUR_MAX 2u
#define TD_POSTFX_PREFILTER 3u
#define TD_POSTFX_GATHER 4u
#define TD_POSTFX_MEDIAN 5u
#define TD_POSTFX_UPSCALE 6u

#define TD_POSTFX_TILE 8u  // half-res pixels a tile side
// A half-resolution sample: r, g, b, coc (half-res pixels, signed), z (view depth), spec (1: a
// bright highlight), radius (|coc| / 2), alpha (1 / (pi r^2)).
#define TD_HALF_SAMPLE 8u
// The gather's 81 taps, computed on the host: x, y, dist (unit kernel), and the aperture's
// extent towards the centre for far- and near-field spots.
#define TD_POSTFX_TAPS 81u
#define TD_TAP_FLOATS 5u

struct PostfxDofArgs {
  TD_ADDR hdr, coc, specular;     // the frame's (specular: 4 floats a pixel)
  TD_ADDR halfSamples;            // TD_HALF_SAMPLE floats a half-res pixel
  TD_ADDR tileMax, neighbourMax;  // a float a tile
  TD_ADDR gathered, bokeh;        // half res: 3 and 2 floats a pixel
  TD_ADDR filtered;               // the median of gathered
  TD_ADDR taps;                   // TD_POSTFX_TAPS x TD_TAP_FLOATS
  TD_ADDR src, dst;               // the upscale's: half res to the frame, `channels` floats
  TD_UINT width, height, halfWidth, halfHeight, tilesX, tilesY, channels, pad;
  TD_FLOAT lensK, focus, specularThreshold, bokehLuminance, depthRange, invRange;
};

// The push constants of a kernel run in stages (postfx_dof, dof_reconstruction): the arguments'
// address and the stage.
struct DofStagePush {
  TD_ADDR args;
  TD_UINT stage, pad;
};

#define TD_COMPOSITE_RT_CHANNELS 9u  // rt_recon (dof::RtChannels)

// dof_reconstruction's stages: the 3x3 median, level 0 of the mips (premultiplied by coverage),
// each coarser level (downsampleBox of the one before), the reconstruction.
#define TD_RECON_MEDIAN 0u
#define TD_RECON_PREMULTIPLY 1u
#define TD_RECON_DOWNSAMPLE 2u
#define TD_RECON_GATHER 3u
#define TD_RECON_TAPS 25u  // the centre and rings of 8 and 16: ring, cos, sin each
#define TD_RECON_LEVELS 4u
struct DofReconstructionArgs {
  TD_ADDR rtColor, variance, filtered, rtRecon, taps;
  TD_ADDR mips[TD_RECON_LEVELS];
  TD_ADDR src, dst;  // the downsample's levels
  TD_UINT width, height, srcWidth, srcHeight;
  TD_UINT dstWidth, dstHeight, levels, pad;
  TD_INT mipWidth[TD_RECON_LEVELS], mipHeight[TD_RECON_LEVELS];
  TD_FLOAT varianceWeight, lodScale, scale, pad2;
};
struct DofCompositeArgs {
  TD_ADDR sharp, coc, postfx, bokeh, rt, dof;  // postfx, bokeh, rt: 0 when absent
  TD_UINT width, height, rtWidth, rtHeight;
  TD_UINT rtMode, useBokeh, sharpBackground, pad;
  TD_FLOAT farBlend, fineCoc, scaleX, scaleY;
};

// A view as dof_accumulation reprojects into it: last frame's projection (row-major), its
// viewport, whether its camera moved.
struct DofAccumulationView {
  TD_FLOAT prevViewProj[16];
  TD_INT x, y, width, height;
  TD_INT cameraMoved, perspective, pad0, pad1;
};
// counters: two uint64 the kernel adds to, the variance summed (units of 2^-32) and the pixels
// whose variance exceeds 1e-6.
struct DofAccumulationArgs {
  TD_ADDR rtNear, rtFar, rtHit, rtFarPosition, motion;
  TD_ADDR prevNear, prevFar, prevMoments;  // 0: no history that fits
  TD_ADDR accNear, accFar, accMoments, rtColor, variance;
  TD_ADDR views, counters;
  TD_UINT width, height, frameWidth, frameHeight;
  TD_UINT motionWidth, motionHeight, viewCount, adaptive;
  TD_FLOAT scale, minAlpha, motionPixels, pad;
};

// ray_mask's stages (RayMaskPass::execute): the filtered quantities' input (inverse depth and
// normals), their 2x2 reduction to the mask (half resolution), the near field and the pixels the
// composite's fine gather takes, the 16x16 tiles' largest near radius and its 3x3 neighbourhood
// max (dilate), the rays per pixel (eq. 2-4). The Gaussian and the Sobel run through convolve.comp.
#define TD_MASK_INPUT 0u
#define TD_MASK_DOWNSAMPLE 1u
#define TD_MASK_NEAR 2u
#define TD_MASK_TILE_MAX 3u
#define TD_MASK_NEIGHBOUR_MAX 4u
#define TD_MASK_RAYS 5u
#define TD_MASK_TILE 16u
struct RayMaskArgs {
  TD_ADDR position, normal, depth, coc, bokeh, variance;  // bokeh, variance: 0 when absent
  TD_ADDR inverseDepth, blurred;  // 4 floats a frame pixel: d / z and the normal, then blurred
  TD_ADDR low, gx, gy;            // 4 floats a mask pixel: reduced (or blurred), its gradients
  TD_ADDR nearFine;               // 2 floats a mask pixel: near radius, fine (1: no rays)
  TD_ADDR tileMax, tileNear;      // a float a tile
  TD_ADDR mask, counters;         // counters: 2 uint64, rays and masked pixels
  TD_UINT width, height, maskWidth, maskHeight;
  TD_UINT scale, tilesX, tilesY, dilate;
  TD_FLOAT eyeX, eyeY, eyeZ, focus;
  TD_FLOAT forwardX, forwardY, forwardZ, fineCoc;
  TD_FLOAT s, varianceWeight, m, pad;
};

// A separable filter's pass (core/image_filters.cpp convolve1d): out[x] = sum of w[t] in[x + t]
// over t = -radius..radius in order, edges clamped, zero weights skipped.
struct ConvolveArgs {
  TD_ADDR src, dst, weights;
  TD_UINT width, height, channels, radius;
  TD_UINT horizontal, pad;
};
#endif
