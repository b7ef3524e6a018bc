// Arguments of nh_denoise.comp (C++ and GLSL): Peres 2022's non-homogeneous À-Trous
// (passes/foveated/atrous.h, nh_denoise.h) in stages. The filter's planes are two states of 5
// floats a pixel (colour r, g, b, the estimate's variance, known; with the variance colour
// weight 9: then the guide's colour and variance), one level reading one and writing the other.
#ifndef TANDEM_GPU_NH_DENOISE_ARGS_H
#define TANDEM_GPU_NH_DENOISE_ARGS_H
#include "foveated_args.h"

#define TD_NH_SETUP 0u   // inputs -> state 0; region sizes; partial luminance sums (L̄)
#define TD_NH_NOISE 1u   // levels_from = variance: partial sums of each region's noise
#define TD_NH_REDUCE 2u  // one group: the partial sums -> stats
#define TD_NH_LEVEL 3u   // one À-Trous level of one region
#define TD_NH_OUTPUT 4u  // the filtered state -> denoised
// The variance colour weight's preparation (nh_denoise.cpp), before the levels:
#define TD_NH_PREFILTER 5u  // state `from` -> the other: each sampled pixel's variance prefiltered
#define TD_NH_PREFILL 6u    // state `from` -> the other: holes take a neighbour's estimate
#define TD_NH_GUIDE 7u      // state `from`, in place: the first level's guide

#define TD_NH_GROUP 256u  // invocations of a setup or noise group (16 x 16): one partial each
// Floats a group: luminance sum, noise sum of regions 0, 1, 2, measured variance sum.
#define TD_NH_PARTIALS 5

// Counts (uints, by atomics): sampled pixels; per region: pixels, listed pixels, pixels whose
// noise was measured; sampled pixels with a measured variance.
#define TD_NH_SAMPLED 0
#define TD_NH_TOTAL 1
#define TD_NH_LISTED 4
#define TD_NH_USED 7
#define TD_NH_MEASURED 10
#define TD_NH_COUNTS 11
// Stats (floats, by the reduce stage): L̄, each region's mean squared noise, the mean measured
// variance (the prefilter's fallback).
#define TD_NH_MEAN 0
#define TD_NH_NOISE_R 1
#define TD_NH_VAR_FALLBACK 4
#define TD_NH_STATS 5

struct NhDenoiseArgs {
  TD_ADDR views;                    // NhView[viewCount]
  TD_ADDR noisy, variance, direct;  // variance, direct: 0 when absent (or split = none)
  TD_ADDR normal, position, depth, diffuse, emission, mask, layer;
  TD_ADDR state[2];
  TD_ADDR partials;  // float[groups * TD_NH_PARTIALS]
  TD_ADDR counts;    // uint[TD_NH_COUNTS]
  TD_ADDR stats;     // float[TD_NH_STATS]
  TD_ADDR denoised;
  TD_UINT width, height, viewCount, regions;  // regions: 0 one, 1 two, 2 three
  TD_UINT groups;                             // partials written by the setup and noise stages
  TD_UINT demodulate;
  TD_FLOAT sigmaColor, sigmaNormal, sigmaPosition, sigmaVariance;
  TD_UINT guided;       // the variance colour weight (pt_variance given)
  TD_UINT stateFloats;  // 5, or 9 when guided
  TD_UINT pad0, pad1;
};

struct NhStagePush {
  TD_ADDR args;
  TD_UINT stage;
  TD_UINT from;  // TD_NH_LEVEL: the state read (the other is written)
  TD_INT step, iteration, region, pad;
};
#endif
