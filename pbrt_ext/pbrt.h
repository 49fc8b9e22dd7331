// pbrt_ext: the vocabulary every header shares (pbrt-v4's src/pbrt/pbrt.h, reduced).
#pragma once

#include <cstdint>

#if defined(__CUDACC__)
#define PBRT_CPU_GPU __host__ __device__
#define PBRT_IS_GPU_CODE 1
#else
#define PBRT_CPU_GPU
#endif

namespace pbrt {

// Single precision throughout, as pbrt-v4's default build.
using Float = float;

}  // namespace pbrt
