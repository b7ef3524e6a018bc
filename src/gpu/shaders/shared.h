// Included by C++ and GLSL: the scalar types of structures both sides read (kernel arguments in
// push constants, records in buffers). GLSL lays them out with the scalar block layout, C++ as
// plain structs: keep 64-bit members 8-byte aligned and sizes multiples of 8.
#ifndef TANDEM_GPU_SHARED_H
#define TANDEM_GPU_SHARED_H
#ifdef __cplusplus
#include <cstdint>
#define TD_ADDR uint64_t
#define TD_UINT uint32_t
#define TD_INT int32_t
#define TD_FLOAT float
#else
#define TD_ADDR uint64_t
#define TD_UINT uint
#define TD_INT int
#define TD_FLOAT float
#endif
#endif
