#pragma once
// RT_HD marks code shared by the CUDA and CPU back ends: __host__ __device__ under nvcc, nothing
// elsewhere. Such code is header-only, has no virtual functions, exceptions or STL containers.
#if defined(__CUDACC__)
#define RT_HD __host__ __device__
#define RT_DEVICE_CODE 1
#else
#define RT_HD
#endif

#if defined(__CUDA_ARCH__)
#define RT_ON_GPU 1
#endif

// Forces inlining in host code: g++ leaves some small hot functions of the traversal loops a call
// there (bench/results/cpu-triangle-inline-2026-12-03.txt); nvcc inlines them without being told.
#if defined(__CUDACC__)
#define RT_HOST_ALWAYS_INLINE
#else
#define RT_HOST_ALWAYS_INLINE [[gnu::always_inline]]
#endif
