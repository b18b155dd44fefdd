#include "engine/ecs/scheduler.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "engine/core/timer.h"

namespace rtrt::ecs {

Scheduler::Scheduler() : Scheduler(kDefaultPhases) {}

Scheduler::Scheduler(std::span<const std::string_view> phases) {
    for (const std::string_view phase : phases) {
        const bool repeated = std::any_of(phaseTimings_.begin(), phaseTimings_.end(),
                                          [&](const PhaseTiming& p) { return p.name == phase; });
        if (repeated) {
            throw std::invalid_argument("Scheduler: phase '" + std::string(phase) +
                                        "' is listed twice");
        }
        phaseTimings_.push_back({std::string(phase), 0.0});
    }
}

void Scheduler::AddSystem(std::string_view phase, std::string name, SystemFn fn) {
    const auto phaseIt = std::find_if(phaseTimings_.begin(), phaseTimings_.end(),
                                      [&](const PhaseTiming& p) { return p.name == phase; });
    if (phaseIt == phaseTimings_.end()) {
        throw std::invalid_argument("Scheduler::AddSystem: system '" + name +
                                    "' names unknown phase '" + std::string(phase) + "'");
    }
    const bool taken = std::any_of(systemTimings_.begin(), systemTimings_.end(),
                                   [&](const SystemTiming& s) { return s.name == name; });
    if (taken) {
        throw std::invalid_argument("Scheduler::AddSystem: system name '" + name +
                                    "' is already taken");
    }
    const auto phaseIndex = static_cast<size_t>(phaseIt - phaseTimings_.begin());
    // After the last system of this phase or of an earlier one.
    const auto at = std::upper_bound(systems_.begin(), systems_.end(), phaseIndex,
                                     [](size_t p, const System& s) { return p < s.phase; });
    const auto offset = at - systems_.begin();
    systemTimings_.insert(systemTimings_.begin() + offset, {phaseIt->name, std::move(name), 0.0});
    systems_.insert(at, {phaseIndex, std::move(fn)});
}

void Scheduler::RunFrame(Registry& registry, float dt) {
    size_t next = 0;
    for (size_t phase = 0; phase < phaseTimings_.size(); ++phase) {
        const Stopwatch phaseClock;
        {
            const ScopedDeferral deferral(registry);  // flushes when the phase's systems are done
            for (; next < systems_.size() && systems_[next].phase == phase; ++next) {
                const Stopwatch clock;
                systems_[next].fn(registry, dt);
                systemTimings_[next].milliseconds = clock.Milliseconds();
            }
        }
        phaseTimings_[phase].milliseconds = phaseClock.Milliseconds();
    }
}

}  // namespace rtrt::ecs
