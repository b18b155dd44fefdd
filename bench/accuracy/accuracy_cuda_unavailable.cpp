#include <stdexcept>

#include "bench/accuracy/accuracy_renderer.h"

namespace rtrt {

CudaAccuracyRun RunAccuracyCuda(const RenderScene&, const RenderSettings&, uint32_t, int, int) {
    throw std::runtime_error("this build has no CUDA back end; use --backend cpu");
}

}  // namespace rtrt
