#pragma once
/// CANOPY_HD marks geometry that both backends run: `__host__ __device__` under nvcc, nothing on
/// the host compiler, so there is one implementation of every predicate (cf. cuBQL math/common.h).
#if defined(__CUDACC__)
#define CANOPY_HD __host__ __device__
#else
#define CANOPY_HD
#endif
