#pragma once
// Device memory of the primary-hit kernel (trace_launch.cuh): a closest hit per pixel, and a ray
// cursor per row band that may trace at the same time (FrameSplit's bands, on streams of their
// own).
#include <cstdint>
#include <stdexcept>
#include <string>

#include "engine/bvh/traversal/two_level_traversal.h"
#include "engine/core/device_buffer.h"
#include "engine/render_rt/scene_features.h"

namespace rtrt {

// One band's view of the buffers: the frame's hits (indexed y * width + x, so that bands write
// apart) and the cursor its kernel hands rays out from.
struct PrimaryHitScratch {
    SceneHit* hits = nullptr;  // null: no primary-hit kernel; each pixel traces its own
    uint32_t* cursor = nullptr;
};

class PrimaryHitBuffers {
  public:
    static constexpr uint32_t kMaxBands = 64;

    // The buffers for band `band` (below kMaxBands) of a width x height frame traced with
    // `features`: none unless its scenes have many instances (kFeatureManyInstances), the only
    // ones that use the kernel. The hits grow as needed: call for band 0 first, before other
    // bands' kernels run.
    PrimaryHitScratch For(uint32_t features, uint32_t width, uint32_t height, uint32_t band) {
        if ((features & kFeatureManyInstances) == 0) return {};
        if (band >= kMaxBands)
            throw std::out_of_range("primary hits: band " + std::to_string(band) + " of at most " +
                                    std::to_string(kMaxBands));
        const size_t pixels = size_t(width) * height;
        if (hits_.Size() < pixels) hits_.Resize(pixels);
        if (cursors_.Size() < kMaxBands) cursors_.Resize(kMaxBands);
        return {hits_.Data(), cursors_.Data() + band};
    }

  private:
    DeviceBuffer<SceneHit> hits_;
    DeviceBuffer<uint32_t> cursors_;
};

}  // namespace rtrt
