#pragma once
// The GPU's two traversals of a scene of many instances (scene_features.h): the nested form (a
// BLAS loop in each TLAS leaf reached, scene_traversal.h) and the single loop over both levels
// (two_level_traversal.h). They find the same hits, so the image does not depend on the form;
// which is faster depends on the scene and the view. On the H100 the single loop traced the
// instance grid (a dense lattice of 11,102-triangle dragons) 13-30% faster, the nested form the
// played demos of 465-10,005 instances 17-28% faster
// (bench/results/traversal-form-h100-2026-12-05.txt). So the CUDA frame renderer measures them
// on the scene as it plays (TraversalChooser); where nothing is measured (a one-shot render, the
// bands of a frame split over several GPUs) the nested form, which won every played scene.
#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/render_rt/scene_features.h"

namespace rtrt {

enum class TraversalForm : uint8_t {
    kAuto,        // measured as frames play (TraversalChooser), else the nested form
    kNested,      // always the nested form
    kSingleLoop,  // always the single loop
};

// Parses "auto", "nested" or "single"; false for anything else.
bool ParseTraversalForm(std::string_view name, TraversalForm* form);
std::string_view TraversalFormName(TraversalForm form);

// The features a trace of a scene of many instances (kFeatureManyInstances set, the single loop's
// bit) launches with: the bit kept for kSingleLoop, cleared for kNested and, where nothing is
// measured, kAuto. Scenes of fewer instances always take the nested form.
inline uint32_t WithTraversalForm(uint32_t features, TraversalForm form) {
    if (form == TraversalForm::kSingleLoop) return features;
    return features & ~kFeatureManyInstances;
}

// Which form a frame takes, measured on the frames themselves. A trial traces kTrialFrames frames
// alternating the two forms (so that a scene that changes as it plays moves both forms' times
// alike), then keeps the form with the smaller median trace time; the other takes over only when
// it was faster by more than kSwitchMargin, so that noise does not flip the choice. Trials
// start on the first frame, again kSettledFrames frames after each decision (the scene and the
// view change as they play), and at once when the configuration (features, view, size) changes.
// Times arrive a frame or two after their frames are queued (as the GPU's events are read);
// those of an earlier trial or configuration are ignored, and a trial whose times do not all
// arrive starts again.
class TraversalChooser {
  public:
    static constexpr uint32_t kTrialFrames = 8;
    static constexpr uint32_t kSettledFrames = 240;
    static constexpr double kSwitchMargin = 0.03;

    // What a frame was traced with; handed back with its time.
    struct Ticket {
        uint64_t trial = 0;  // 0: not a trial frame
        bool singleLoop = false;
    };

    // The form of the next frame under `configuration` (any value that changes when something
    // the trace time depends on, other than the scene's motion, changes).
    Ticket Next(uint64_t configuration);
    // The trace time of a frame Next gave `ticket`.
    void Report(Ticket ticket, double traceMs);
    // The form frames take outside trials.
    bool SettledOnSingleLoop() const { return settledSingleLoop_; }
    uint64_t Decisions() const { return decisions_; }

  private:
    void StartTrial();
    void Decide();

    uint64_t configuration_ = 0;
    bool configured_ = false;
    bool settledSingleLoop_ = false;
    uint64_t trial_ = 0;    // the current trial's number; trials count from 1
    bool inTrial_ = false;  // issuing its frames or waiting for their times
    uint32_t issued_ = 0;   // trial frames issued
    uint32_t waited_ = 0;   // frames issued since the last trial frame, while waiting
    uint32_t settledFor_ = 0;
    uint64_t decisions_ = 0;
    std::vector<double> times_[2];  // this trial's times: nested, single loop
};

}  // namespace rtrt
