#pragma once
// `rtrt play SCENE...` in a window: the scene plays on its timeline while the user flies around,
// spawns, picks, drags and deletes objects, toggles effects and watches the overlay.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/render_rt/frame_renderer.h"
#include "game/app/input_script.h"

namespace rtrt {

struct WindowOptions {
    std::vector<std::string> scenes;  // PageDown / PageUp cycle through them
    std::string backend = "auto";     // auto (CUDA when usable), cpu, cuda
    GpuSplit gpus;                    // the CUDA back end's GPUs (the first shows the frame)
    bool contactsOnGpu = false;       // the rigid bodies' contacts solved on the first GPU
    uint32_t width = 1280, height = 720;
    bool vsync = true;
    // Waits for the GPU (glFinish) after each display stage, so that the stage times printed at
    // the end are each stage's own, GPU work included, rather than wherever the driver blocks.
    bool finishStages = false;
    std::string record;  // a video (.mp4...), or a folder for each frame shown as frame_NNNNN.png
    std::optional<InputScript> script;  // scripted input, for tests (loaded before the window)
    int frames = 0;                     // stop after this many frames (0: when the window closes)
    float fps = 60.0f;  // the fixed time step with --record or --script; else the wall clock
    std::optional<float> exposureEv;  // over each scene's own (, and . change it)
    std::string toneMap;              // over each scene's own
};

// Runs until the window closes (or the script or frame count ends); returns the exit status.
int RunWindow(const WindowOptions& options);

}  // namespace rtrt
