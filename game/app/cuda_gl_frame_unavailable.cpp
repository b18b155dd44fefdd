// Built without CUDA: the window always uploads frames from the host.
#include "game/app/cuda_gl_frame.h"

namespace rtrt {

CudaGlFrame::~CudaGlFrame() = default;
bool CudaGlFrame::Register(uint32_t, std::string* why) {
    if (why) *why = "this rtrt was built without CUDA";
    return false;
}
void CudaGlFrame::Unregister() {}
void CudaGlFrame::Present(const vec3*, uint32_t, uint32_t, const OutputTransform&) {}

}  // namespace rtrt
