#pragma once
// What a frame is traced with (size, depth, view, features, samples), which back end traces it,
// and what tracing it counted.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/render_rt/scene_features.h"
#include "engine/render_rt/traversal/traversal_form.h"

namespace rtrt {

enum class Backend { kCpu, kCuda };

struct RenderSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    uint32_t maxDepth = 4;
    ViewMode view = ViewMode::kShaded;
    uint32_t enabledFeatures = kAllFeatures;  // a feature runs only if the scene has it too
    uint32_t samplesPerPixel = 1;  // shaded view; a square (1, 4, 9...), see pixel_sample.h
    // CUDA: the frame's rows split into this many bands, each traced on its own stream, the
    // shares following each band's last trace time (split/frame_split.h): the split of several
    // GPUs, on one. The image is the same for any count. The CPU back end ignores it.
    uint32_t traceBands = 1;
    // CUDA, scenes of many instances: the scene traversal (traversal/traversal_form.h). The
    // image is the same for any form. The CPU back end ignores it.
    TraversalForm traversal = TraversalForm::kAuto;
};

struct RenderStats {
    uint64_t rays = 0;  // primary, shadow and secondary rays traced
};

// Whether the CUDA back end can run here; if not, why (for the CLI's message).
bool CudaBackendAvailable(std::string* why);

// The CUDA devices this machine has (0 where the CUDA back end cannot run).
uint32_t CudaDeviceCount();

// The GPUs a user's --gpus names: "all" (every device), or a count N (devices 0 to N-1). False,
// with why, for a count the machine does not have or text that is neither.
bool ChooseGpus(const std::string& choice, std::vector<int>* devices, std::string* why);

// The back end a user's choice names: "cpu", "cuda", or "auto" (CUDA where it can run, else the
// CPU). False, with why, for "cuda" where it cannot run, or an unknown name.
bool ChooseBackend(const std::string& choice, Backend* backend, std::string* why);

}  // namespace rtrt
