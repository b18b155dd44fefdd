#include "game/app/cuda_gl_frame.h"

// cuda_gl_interop.h needs the GL types first.
#include "game/app/gl.h"
// clang-format off
#include <cuda_gl_interop.h>
// clang-format on

#include "engine/core/cuda_check.h"

namespace rtrt {
namespace {

__global__ void PresentKernel(const vec3* frame, uint32_t width, uint32_t height,
                              OutputTransform transform, cudaSurfaceObject_t surface) {
    const uint32_t x = blockIdx.x * blockDim.x + threadIdx.x;
    const uint32_t y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= width || y >= height) return;
    // The same output transform as image files and the CPU upload.
    const vec3 c = ApplyOutputTransform(frame[size_t(y) * width + x], transform);
    // Texture row 0 holds the image's top row, as the CPU upload leaves it.
    surf2Dwrite(make_uchar4(DisplayByte(c.x), DisplayByte(c.y), DisplayByte(c.z), 255), surface,
                int(x * 4), int(y));
}

}  // namespace

CudaGlFrame::~CudaGlFrame() { Unregister(); }

bool CudaGlFrame::Register(uint32_t texture, std::string* why) {
    Unregister();
    unsigned int count = 0;
    int devices[1];
    if (cudaGLGetDevices(&count, devices, 1, cudaGLDeviceListAll) != cudaSuccess || count == 0) {
        cudaGetLastError();  // clear the sticky-free error so later calls are not blamed
        if (why) *why = "the OpenGL context does not run on a CUDA device";
        return false;
    }
    cudaGraphicsResource_t resource = nullptr;
    const cudaError_t status = cudaGraphicsGLRegisterImage(
        &resource, texture, GL_TEXTURE_2D, cudaGraphicsRegisterFlagsSurfaceLoadStore);
    if (status != cudaSuccess) {
        cudaGetLastError();
        if (why) *why = std::string("cudaGraphicsGLRegisterImage: ") + cudaGetErrorString(status);
        return false;
    }
    resource_ = resource;
    return true;
}

void CudaGlFrame::Unregister() {
    if (!resource_) return;
    cudaGraphicsUnregisterResource(static_cast<cudaGraphicsResource_t>(resource_));
    resource_ = nullptr;
}

void CudaGlFrame::Present(const vec3* deviceFrame, uint32_t width, uint32_t height,
                          const OutputTransform& transform) {
    auto resource = static_cast<cudaGraphicsResource_t>(resource_);
    RT_CUDA_CHECK(cudaGraphicsMapResources(1, &resource));
    cudaArray_t array = nullptr;
    RT_CUDA_CHECK(cudaGraphicsSubResourceGetMappedArray(&array, resource, 0, 0));
    cudaResourceDesc desc{};
    desc.resType = cudaResourceTypeArray;
    desc.res.array.array = array;
    cudaSurfaceObject_t surface = 0;
    RT_CUDA_CHECK(cudaCreateSurfaceObject(&surface, &desc));
    const dim3 block(16, 16);
    const dim3 grid((width + 15) / 16, (height + 15) / 16);
    PresentKernel<<<grid, block>>>(deviceFrame, width, height, transform, surface);
    RT_CUDA_CHECK_LAUNCH();
    RT_CUDA_CHECK(cudaDestroySurfaceObject(surface));
    RT_CUDA_CHECK(cudaGraphicsUnmapResources(1, &resource));
}

}  // namespace rtrt
