#pragma once
// The seam between a running scene and a back end. Every frame the runtime hands over what
// changed (instance records rewritten or added, and whether instances were added or removed);
// the frame renderer brings its own copy of the scene up to date (the TLAS is its business: an
// LBVH refit or rebuilt under the TlasPolicy, on the host or on the device), traces into a
// target, answers picking rays against what it traced, and reports per-stage times. One factory
// chooses the implementation; the window, `rtrt play --headless` and `rtrt bench frame` use it.
#include <array>
#include <memory>
#include <span>
#include <vector>

#include "engine/bvh/tlas/dynamic_tlas.h"
#include "engine/bvh/tlas/tlas.h"
#include "engine/render_rt/image.h"
#include "engine/render_rt/render_scene.h"
#include "engine/render_rt/render_settings.h"

namespace rtrt {

// One frame's stages. The GPU times them with CUDA events and collects them a frame or two later,
// so that no frame waits for the GPU to read them; the CPU times them with the host clock.
struct FrameTimes {
    uint64_t frame = 0;     // which Trace these are (1 = the first); 0: none known yet
    double deformMs = 0.0;  // deforming meshes skinned / morphed into their triangles
    double blasMs = 0.0;    // their BLASes refit or rebuilt, and the SAH costs of the policy
    double uploadMs = 0.0;  // changed instance records (and their world boxes) sent
    double tlasMs = 0.0;    // LBVH rebuild or refit, and its SAH cost where the policy needs one
    double traceMs = 0.0;
    uint32_t uploaded = 0;     // instance records sent to the device
    uint32_t deformed = 0;     // deforming BLASes brought up to date
    uint32_t blasRebuilt = 0;  // of them rebuilt rather than refit
    bool tlasRebuilt = false;
    // The GPU traced a scene of many instances with the single loop over both levels rather
    // than the nested form (traversal/traversal_form.h); false on the CPU.
    bool singleLoop = false;
    float tlasSahCost = 0.0f;  // the cost the rebuild policy last saw (the GPU computes none
                               // while the policy rebuilds whenever records changed)
    uint64_t rays = 0;         // rays traced, when Trace was asked to count them
    // A frame split over several GPUs (GpuSplit): traceMs runs from the display GPU's start of the
    // trace until every band is gathered there; each GPU's own band took gpuTraceMs, over
    // gpuRows rows. On one GPU, its trace and rows.
    static constexpr uint32_t kMaxGpus = 16;
    uint32_t gpus = 1;
    std::array<double, kMaxGpus> gpuTraceMs{};
    std::array<uint32_t, kMaxGpus> gpuRows{};
};

// Where a CUDA frame renderer traces. Each frame's rows are split over `devices`, the shares
// following each GPU's last trace times; the first device is the display GPU, where the bands are
// gathered (for CUDA-GL interop or the output file). Empty: the current device alone. A device
// may be named more than once (tests split a frame over several renderers of one GPU).
struct GpuSplit {
    enum class Tlas {
        kBuildOnEach,      // every GPU builds the TLAS from the same instance records
        kCopyFromDisplay,  // the display GPU builds it; the others copy its records and nodes
    };
    std::vector<int> devices;
    Tlas tlas = Tlas::kBuildOnEach;
};

class FrameRenderer {
  public:
    virtual ~FrameRenderer() = default;
    virtual Backend Kind() const = 0;

    // Brings the renderer's copy of the scene up to date with `scene`, given what changed.
    virtual void Update(const RenderScene& scene, const SceneChanges& changes) = 0;
    // Traces a frame of the scene as last updated (camera and settings from the arguments). With
    // `image`, waits for the frame and copies it there (linear RGB); without, the frame may still
    // be in flight on the device when this returns (DeviceFrame(), Finish()). With `stats`, rays
    // are counted: into *stats when the call waited for the frame (an image, or the CPU), and
    // into the frame's Times().rays in any case.
    virtual void Trace(const RenderScene& scene, const RenderSettings& settings, Image* image,
                       RenderStats* stats = nullptr) = 0;
    // Waits for the last traced frame; its times are then Times().
    virtual void Finish() = 0;
    // The closest hit of one ray through the structures the last frame was traced with (the
    // window's picking). False on a miss.
    virtual bool Pick(const Ray& ray, SceneHit* hit) = 0;
    // The latest frame whose stage times are known (see FrameTimes).
    virtual const FrameTimes& Times() const = 0;
    // The last traced frame in device memory (width x height linear RGB) for CUDA-GL interop;
    // null where frames live on the host.
    virtual const vec3* DeviceFrame() const = 0;
    // The TLAS as the renderer holds it (tests compare the back ends' trees).
    virtual Tlas CurrentTlas() const = 0;
};

// The frame renderer of `backend` over `scene` (its materials, lights and textures are taken
// now; BLASes and deformations the scene gains later are taken by Update); CUDA traces on `gpus`,
// the CPU ignores them. Throws std::runtime_error when the back end cannot run here, saying why.
std::unique_ptr<FrameRenderer> MakeFrameRenderer(Backend backend, const RenderScene& scene,
                                                 TlasPolicy policy = {},
                                                 BlasRebuildPolicy blasPolicy = {},
                                                 const GpuSplit& gpus = {});

}  // namespace rtrt
