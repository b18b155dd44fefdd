#pragma once
// Systems in named phases that run in a fixed order, with a sync point after each phase.
#include <array>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/ecs/registry.h"

namespace rtrt::ecs {

struct SystemTiming {
    std::string phase;
    std::string name;
    double milliseconds = 0.0;  // the last frame's run
};

struct PhaseTiming {
    std::string name;
    double milliseconds = 0.0;  // the last frame's run: its systems and its flush
};

// Runs every phase's systems in the order they were added, phases in the order given. Structural
// changes the systems request are deferred to the end of their phase, so systems of one phase see
// the world as it was when the phase began, and the next phase sees it changed.
class Scheduler {
  public:
    using SystemFn = std::function<void(Registry& registry, float dt)>;

    static constexpr std::array<std::string_view, 4> kDefaultPhases{"input", "simulation",
                                                                    "animation", "extraction"};

    Scheduler();
    // Throws std::invalid_argument on a repeated phase name.
    explicit Scheduler(std::span<const std::string_view> phases);

    // Throws std::invalid_argument for an unknown phase or a system name already taken.
    void AddSystem(std::string_view phase, std::string name, SystemFn fn);

    // Runs one frame; dt is the frame's time step in seconds.
    void RunFrame(Registry& registry, float dt);

    std::span<const SystemTiming> SystemTimings() const { return systemTimings_; }  // run order
    std::span<const PhaseTiming> PhaseTimings() const { return phaseTimings_; }     // phase order

  private:
    struct System {
        size_t phase;
        SystemFn fn;
    };

    std::vector<System> systems_;              // sorted by phase, then by when added
    std::vector<SystemTiming> systemTimings_;  // parallel to systems_
    std::vector<PhaseTiming> phaseTimings_;    // one per phase, in run order
};

}  // namespace rtrt::ecs
