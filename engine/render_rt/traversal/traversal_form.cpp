#include "engine/render_rt/traversal/traversal_form.h"

#include <algorithm>

#include "engine/core/timer.h"

namespace rtrt {
namespace {

// A trial whose times have not all arrived this many frames after its last frame starts again.
constexpr uint32_t kMaxWait = 16;

}  // namespace

bool ParseTraversalForm(std::string_view name, TraversalForm* form) {
    if (name == "auto") {
        *form = TraversalForm::kAuto;
    } else if (name == "nested") {
        *form = TraversalForm::kNested;
    } else if (name == "single") {
        *form = TraversalForm::kSingleLoop;
    } else {
        return false;
    }
    return true;
}

std::string_view TraversalFormName(TraversalForm form) {
    switch (form) {
        case TraversalForm::kNested:
            return "nested";
        case TraversalForm::kSingleLoop:
            return "single";
        default:
            return "auto";
    }
}

TraversalChooser::Ticket TraversalChooser::Next(uint64_t configuration) {
    if (!configured_ || configuration != configuration_) {
        configured_ = true;
        configuration_ = configuration;
        StartTrial();
    }
    if (!inTrial_ && ++settledFor_ > kSettledFrames) StartTrial();
    if (inTrial_ && issued_ < kTrialFrames) {
        // The form in use first, then the other, in turn.
        const bool single = (issued_ % 2 == 0) == settledSingleLoop_;
        ++issued_;
        return {trial_, single};
    }
    if (inTrial_ && ++waited_ > kMaxWait) StartTrial();
    return {0, settledSingleLoop_};
}

void TraversalChooser::Report(Ticket ticket, double traceMs) {
    if (!inTrial_ || ticket.trial != trial_ || !(traceMs >= 0.0)) return;
    times_[ticket.singleLoop ? 1 : 0].push_back(traceMs);
    if (times_[0].size() == kTrialFrames / 2 && times_[1].size() == kTrialFrames / 2) Decide();
}

void TraversalChooser::StartTrial() {
    ++trial_;
    inTrial_ = true;
    issued_ = 0;
    waited_ = 0;
    times_[0].clear();
    times_[1].clear();
}

void TraversalChooser::Decide() {
    const double inUse = Median(times_[settledSingleLoop_ ? 1 : 0]);
    const double other = Median(times_[settledSingleLoop_ ? 0 : 1]);
    if (other < inUse * (1.0 - kSwitchMargin)) settledSingleLoop_ = !settledSingleLoop_;
    inTrial_ = false;
    settledFor_ = 0;
    ++decisions_;
}

}  // namespace rtrt
