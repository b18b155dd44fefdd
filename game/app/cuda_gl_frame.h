#pragma once
// CUDA-GL interop for the window: the display's texture is registered with CUDA once (again after
// a resize), and each frame a kernel writes the traced frame into it through a surface object,
// so the pixels never pass through host memory. Registration fails when the GL context does not
// run on a CUDA device (Mesa's llvmpipe, or a desktop whose GL runs on another GPU); the window
// then copies frames through the host and says so once.
#include <cstdint>
#include <string>

#include "engine/core/math.h"
#include "engine/render_rt/output_transform.h"

namespace rtrt {

class CudaGlFrame {
  public:
    CudaGlFrame() = default;
    ~CudaGlFrame();
    CudaGlFrame(const CudaGlFrame&) = delete;
    CudaGlFrame& operator=(const CudaGlFrame&) = delete;

    // Registers a GL_RGBA8 texture; false with the reason when interop is not possible here.
    bool Register(uint32_t texture, std::string* why);
    void Unregister();
    bool Registered() const { return resource_ != nullptr; }
    // Writes a device frame of linear RGB (width x height, rows top to bottom) into the texture
    // through the output transform, rounded to 8 bits as image files are written.
    void Present(const vec3* deviceFrame, uint32_t width, uint32_t height,
                 const OutputTransform& transform);

  private:
    void* resource_ = nullptr;  // cudaGraphicsResource_t
};

}  // namespace rtrt
