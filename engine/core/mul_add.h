#pragma once
// Device code is compiled without implicit fused multiply-adds (-fmad=false, engine/core's
// CMakeLists.txt), so that a value does not depend on where the compiler placed the code that
// computes it: the traversal forms' kernels then give the same pixels bit for bit. Where a
// multiply-add is hot, the code asks for the fused one here, which the GPU then computes the same
// way in every kernel. The host computes a product and a sum (it compiles with -ffp-contract=off),
// as it did before.
#include "engine/core/rt_hd.h"

namespace rtrt {

// a * b + c: one rounding on the GPU, two on the host.
RT_HD inline float MulAdd(float a, float b, float c) {
#if defined(__CUDA_ARCH__)
    return __fmaf_rn(a, b, c);
#else
    return a * b + c;
#endif
}

}  // namespace rtrt
