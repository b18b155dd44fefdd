#pragma once
// One GPU's part of a frame split over several (multi_gpu_frame_renderer.h): the CUDA frame
// renderer of one device, which also traces a band of rows on request and can take its TLAS from
// another GPU's renderer instead of building it. Every call makes its device current for its
// duration, so callers need not; destroy it with its device current. CUDA code only.
#include <cuda_runtime.h>

#include <memory>

#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/split/frame_split.h"

namespace rtrt {

class GpuBandRenderer : public FrameRenderer {
  public:
    virtual int Device() const = 0;
    // Queues rows `band` of a frame (as Trace would trace them) into this GPU's framebuffer on
    // its default stream, without waiting; the other rows keep what they held. Rays are counted
    // into the frame's Times().rays when countRays.
    virtual void TraceBand(const RenderScene& scene, const RenderSettings& settings, RowBand band,
                           bool countRays) = 0;
    // This GPU's framebuffer of the last traced size (width x height linear RGB), writable: the
    // display GPU's receives the other GPUs' bands.
    virtual vec3* Framebuffer() = 0;
    // From now on, Update copies the instance records and the TLAS nodes from `source` (a renderer
    // of the same scene on another GPU, updated first each frame) rather than uploading and
    // building them here. Null: build here again.
    virtual void CopyTlasFrom(GpuBandRenderer* source) = 0;
    // Recorded on this GPU's stream when the last Update's TLAS was complete.
    virtual cudaEvent_t TlasDone() const = 0;
    // The last Update's records and nodes in this GPU's memory (what CopyTlasFrom copies).
    virtual const Instance* InstanceRecords() const = 0;
    virtual const BvhNode* TlasNodes(uint32_t* nodeCount) const = 0;
    // The stage times of traced frame `frame` (Times().frame numbering), waiting for it if need
    // be; false once it is older than the last few.
    virtual bool TimesOf(uint64_t frame, FrameTimes* times) = 0;
};

// The renderer of one GPU (its own copy of the scene: BLASes, materials, textures).
std::unique_ptr<GpuBandRenderer> MakeGpuBandRenderer(int device, const RenderScene& scene,
                                                     TlasPolicy policy,
                                                     BlasRebuildPolicy blasPolicy);

}  // namespace rtrt
