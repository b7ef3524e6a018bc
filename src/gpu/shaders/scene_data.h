// The scene's shading data on the GPU (C++ and GLSL): materials, textures with their mip chains,
// lights as shading prepares them, per-object vertex attributes and the sky, reached from one
// SceneArgs record in device memory whose address kernels take in their push constants.
#ifndef TANDEM_GPU_SCENE_DATA_H
#define TANDEM_GPU_SCENE_DATA_H
#include "shared.h"

// Material flags.
#define TD_MAT_CASTS_SHADOWS 1u
#define TD_MAT_DOUBLE_SIDED 2u
#define TD_MAT_ALPHA_MASK 4u
#define TD_MAT_ALPHA_BLEND 8u
#define TD_MAT_UV_ROTATION 16u

// Material (scene/material.h) with the UV rotation's cosine and sine worked out on the host.
struct GpuMaterial {
  TD_FLOAT emission[3], ambient[3], diffuse[3], diffuseOpacity;
  TD_FLOAT specular[3], specularExponent;
  TD_FLOAT reflectivity, ior, opacity, transmissionFilter[3];
  TD_FLOAT tiling[2], offset[2], uvCos, uvSin;
  TD_FLOAT alphaCutoff, normalScale, occlusionStrength;
  TD_FLOAT baseColor[3], metallic, roughness;
  TD_INT diffuseTexture, emissionTexture, specularTexture, normalTexture;
  TD_INT metallicRoughnessTexture, occlusionTexture;
  TD_UINT flags;  // TD_MAT_*
  TD_UINT pad;
};

// Texture: `levels` mip levels from `firstLevel` in the level table; wrap modes as WrapMode.
struct GpuTexture {
  TD_UINT firstLevel, levels, wrapS, wrapT;
  TD_UINT srgb, size;  // size: max(width, height) of level 0 (level of detail)
};
struct GpuTextureLevel {
  TD_UINT offset;  // first texel (RGBA8 in one uint) in the texel array
  TD_INT width, height;
  TD_UINT pad;
};

// PreparedLight (shading/blinn_phong.h); type as LightType.
struct GpuLight {
  TD_UINT type, castsShadows, hemisphere, pad;
  TD_FLOAT power[3], range;
  TD_FLOAT position[3], attConstant;
  TD_FLOAT direction[3], attLinear;
  TD_FLOAT attQuadratic, cosOuter, cosInner, cosinePower;
};

// Object: its material and where its vertices (world-space positions, normals, tangents; UVs)
// and its triangles' vertex indices start in the shared arrays; an object moving while the
// shutter is open has `motionSteps` time steps of positions and normals (FrameObject's
// stepPositions, stepNormals), vertex i's step s at firstStep + i * motionSteps + s.
struct GpuObject {
  TD_UINT material, firstVertex, firstIndex, hasUvs;
  TD_UINT hasTangents, motionSteps, firstStep, pad;
};

struct SceneArgs {
  TD_ADDR nodes, triangles, trianglePrim, objectRoot;  // the BVHs (bvh.h TraceArgs)
  TD_ADDR objects, materials, textures, levels, texels, lights;
  TD_ADDR positions, normals, tangents, uvs, indices;  // vertices: 3, 3, 4, 2 floats; 3 uints
  TD_ADDR decode;                         // 512 floats: sRGB byte -> linear, then byte / 255
  TD_ADDR objectMotion, motionTriangles;  // bvh.h TraceArgs
  TD_ADDR stepPositions, stepNormals;     // 3 floats a vertex and step (GpuObject)
  TD_UINT topRoot, lightCount;
  TD_INT skyFaces[6];
  TD_FLOAT skyColor[3], ambient[3];
  TD_FLOAT environmentIor;
  TD_UINT pad;
};
#endif
