#pragma once
// Shows a frame in the window: an RGBA8 texture drawn over the whole framebuffer by one triangle.
// The CPU back end uploads its image into the texture; the CUDA back end writes the texture
// directly through CUDA-GL interop (cuda_gl_frame.h).
#include <cstdint>

#include "engine/render_rt/image.h"
#include "engine/render_rt/output_transform.h"

namespace rtrt {

class FrameDisplay {
  public:
    FrameDisplay();  // needs a current OpenGL 3.3 context; throws std::runtime_error on GL errors
    ~FrameDisplay();
    FrameDisplay(const FrameDisplay&) = delete;
    FrameDisplay& operator=(const FrameDisplay&) = delete;

    // Reallocates the texture for frames of this size; returns true when it did (an interop
    // registration of the old texture is then stale).
    bool Resize(uint32_t width, uint32_t height);
    uint32_t Texture() const { return texture_; }
    uint32_t Width() const { return width_; }
    uint32_t Height() const { return height_; }
    // The output transform's display values stored as 8 bits, as image files are written.
    void Upload(const Image& image, const OutputTransform& transform);
    void Draw(int framebufferWidth, int framebufferHeight);
    // What the framebuffer shows now (call after Draw, before the overlay): what screenshots
    // and tests see, through whichever path the frame took (CPU upload or CUDA-GL interop).
    static Image ReadBack(int framebufferWidth, int framebufferHeight);

  private:
    uint32_t texture_ = 0, program_ = 0, vertexArray_ = 0;
    uint32_t width_ = 0, height_ = 0;
};

}  // namespace rtrt
