#pragma once
// The GPU side of a running scene (rtrt play, rtrt bench frame, the window). The BLASes,
// materials and lights go up once; each frame sends only the instance records that changed,
// brings the TLAS up to date on the GPU (an LBVH rebuilt when instances were added, refit
// otherwise, under the runtime's TlasPolicy) and traces into a device framebuffer.
#include <memory>
#include <span>

#include "engine/bvh/tlas/dynamic_tlas.h"
#include "engine/render_rt/renderer.h"

namespace rtrt {

// One frame's GPU stages, timed with CUDA events.
struct GpuFrameTimes {
    double uploadMs = 0.0;  // changed instance records and their world boxes
    double tlasMs = 0.0;    // LBVH rebuild or refit, and its SAH cost
    double traceMs = 0.0;
    uint32_t uploaded = 0;  // instance records sent
    bool tlasRebuilt = false;
    float tlasSahCost = 0.0f;
};

class CudaFrameRenderer {
  public:
    // Uploads the scene; throws std::runtime_error when the CUDA back end is unavailable.
    explicit CudaFrameRenderer(const RenderScene& scene, TlasPolicy policy = {false, 0.25f});
    ~CudaFrameRenderer();
    CudaFrameRenderer(const CudaFrameRenderer&) = delete;
    CudaFrameRenderer& operator=(const CudaFrameRenderer&) = delete;

    // Sends the records at `changed` (indices into scene.instances; instances appended since the
    // last update must be among them) and refits or rebuilds the TLAS.
    void Update(const RenderScene& scene, std::span<const uint32_t> changed);
    // Traces the frame on the GPU and waits for it; copies it into `image` when given.
    void Trace(const RenderScene& scene, const RenderSettings& settings, Image* image,
               RenderStats* stats = nullptr);
    // The closest hit of one ray through the device's TLAS and BLASes (the window's picking): the
    // same structures the frame was traced with. False on a miss.
    bool Pick(const Ray& ray, SceneHit* hit);
    // The last traced frame in device memory (width x height linear RGB), for interop.
    const vec3* DeviceFrame() const;
    // The stages of the last Update and Trace.
    const GpuFrameTimes& Times() const;
    // The TLAS as it is on the device (tests compare it with the CPU's).
    Lbvh DownloadTlas() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace rtrt
