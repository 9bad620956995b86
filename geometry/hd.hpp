#pragma once
/// CANOPY_HD marks geometry that both backends run: `__host__ __device__` under nvcc, nothing on
/// the host compiler, so there is one implementation of every predicate (cf. cuBQL math/common.h).
#if defined(__CUDACC__)
#define CANOPY_HD __host__ __device__
/// On the device, a large predicate kept out of line: the kernels that call it stay small enough
/// for the instruction cache (the host compiler inlines as it sees fit).
#define CANOPY_HD_OUTLINE __host__ __device__ __noinline__
#else
#define CANOPY_HD
#define CANOPY_HD_OUTLINE
#endif
