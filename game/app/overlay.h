#pragma once
// The Dear ImGui overlay: frame-time graph, FPS, per-stage times, counters, the feature toggles
// and the help panel. The model holds what is shown; toggles edit it in place.
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

struct GLFWwindow;

namespace rtrt {

struct StageTimes {
    double simulate = 0, extract = 0, deform = 0, blas = 0, upload = 0, tlas = 0, trace = 0,
           display = 0, frame = 0;
    // The host's time in the display path's parts (display = draw + overlay + swap): the frame
    // into the display texture (CUDA-GL interop or a host upload), the texture drawn, the
    // overlay drawn, and the buffer swap (where the driver makes the host wait for the GPU and
    // the X server when it is behind).
    double present = 0, draw = 0, overlay = 0, swap = 0;
    uint32_t deformed = 0, blasRebuilt = 0;  // deforming BLASes updated, of them rebuilt
    // A frame split over several GPUs: each one's band trace and rows.
    std::vector<double> gpuTrace;
    std::vector<uint32_t> gpuRows;
};

struct OverlayModel {
    static constexpr size_t kHistory = 300;
    std::deque<float> frameMs;  // the last kHistory frames
    StageTimes times;
    uint64_t instances = 0, triangles = 0, rays = 0, tlasNodes = 0;
    std::string scene, backend, display, glRenderer;
    std::string selected;  // the picked object, or empty
    bool paused = false;
    float timeScale = 1.0f;
    // Edited by the overlay.
    bool shadows = true, reflection = true, refraction = true;
    int maxDepth = 2;
    int view = 0;  // ViewMode
    // The output transform (the scene's, over which --exposure/--tone-map, the keys , and .
    // and these controls go).
    float exposureEv = 0.0f;
    int toneMap = 0;  // ToneMap
    bool srgb = false;
    bool useCuda = false;
    bool cudaAvailable = false;
    bool showHelp = false;
    bool show = true;
};

class Overlay {
  public:
    explicit Overlay(GLFWwindow* window);
    ~Overlay();
    Overlay(const Overlay&) = delete;
    Overlay& operator=(const Overlay&) = delete;

    void Draw(OverlayModel& model);  // a whole ImGui frame, rendered into the bound framebuffer
    bool WantsMouse() const;
    bool WantsKeyboard() const;
};

}  // namespace rtrt
