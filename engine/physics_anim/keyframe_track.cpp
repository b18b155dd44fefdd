#include "engine/physics_anim/keyframe_track.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/physics_anim/quat_interp.h"

namespace rtrt::physics {

namespace {

// The key at or before t (clamped to the ends) and the fraction of the way to the next one.
template <typename T>
std::pair<size_t, float> Locate(const Track<T>& track, float t) {
    const std::vector<float>& times = track.times;
    if (times.size() == 1 || t <= times.front()) return {0, 0.0f};
    if (t >= times.back()) return {times.size() - 1, 0.0f};
    const size_t k =
        static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    return {k, (t - times[k]) / (times[k + 1] - times[k])};
}

template <typename T>
std::string ValidateTrack(const Track<T>& track, const char* name) {
    if (track.times.size() != track.values.size()) {
        return std::string(name) + ": " + std::to_string(track.times.size()) + " key times but " +
               std::to_string(track.values.size()) + " values";
    }
    for (size_t i = 0; i < track.times.size(); ++i) {
        if (!std::isfinite(track.times[i]) || track.times[i] < 0.0f) {
            return std::string(name) + ": key time must be finite and >= 0 (key " +
                   std::to_string(i) + ")";
        }
        if (i > 0 && !(track.times[i] > track.times[i - 1])) {
            return std::string(name) + ": key times must increase strictly (key " +
                   std::to_string(i) + ")";
        }
    }
    return {};
}

}  // namespace

vec3 SampleTrack(const Vec3Track& track, float t) {
    const auto [k, u] = Locate(track, t);
    if (u == 0.0f || track.interpolation == Interpolation::kStep) return track.values[k];
    return glm::mix(track.values[k], track.values[k + 1], u);
}

glm::quat SampleTrack(const QuatTrack& track, float t) {
    const auto [k, u] = Locate(track, t);
    if (u == 0.0f || track.interpolation == Interpolation::kStep) return track.values[k];
    if (track.interpolation == Interpolation::kLinear) {
        return Nlerp(track.values[k], track.values[k + 1], u);
    }
    return Slerp(track.values[k], track.values[k + 1], u);
}

float KeyframeClip::Duration() const {
    float duration = 0.0f;
    if (!translation.Empty()) duration = std::max(duration, translation.times.back());
    if (!rotation.Empty()) duration = std::max(duration, rotation.times.back());
    if (!scale.Empty()) duration = std::max(duration, scale.times.back());
    return duration;
}

float ClipTime(const KeyframeClip& clip, double time) {
    const double duration = clip.Duration();
    if (duration <= 0.0) return 0.0f;
    if (clip.wrap == WrapMode::kClamp) return static_cast<float>(std::clamp(time, 0.0, duration));
    double wrapped = std::fmod(time, duration);
    if (wrapped < 0.0) wrapped += duration;
    return static_cast<float>(wrapped);
}

void SampleClip(const KeyframeClip& clip, double time, LocalTransform& pose) {
    const float t = ClipTime(clip, time);
    if (!clip.translation.Empty()) pose.translation = SampleTrack(clip.translation, t);
    if (!clip.rotation.Empty()) pose.rotation = SampleTrack(clip.rotation, t);
    if (!clip.scale.Empty()) pose.scale = SampleTrack(clip.scale, t);
}

std::string ValidateClip(const KeyframeClip& clip) {
    std::string error = ValidateTrack(clip.translation, "translation");
    if (error.empty()) error = ValidateTrack(clip.rotation, "rotation");
    if (error.empty()) error = ValidateTrack(clip.scale, "scale");
    return error;
}

}  // namespace rtrt::physics
