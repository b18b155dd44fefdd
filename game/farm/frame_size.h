#pragma once
// The width and height a farm frame's file holds, from its header alone: frames that tasks
// rendered elsewhere (a Kubernetes Job, say) are taken up by the first `rtrt farm` into their
// folder, and a frame of another size was made with other settings.
#include <cstdint>
#include <string>

namespace rtrt {

struct FrameSize {
    uint32_t width = 0, height = 0;
    bool operator==(const FrameSize&) const = default;
};

// The size in a PNG's IHDR chunk or a binary PPM's (P6) header; nothing for a file that is
// neither, cannot be read or is cut short.
bool ReadFrameSize(const std::string& path, FrameSize* size);

}  // namespace rtrt
