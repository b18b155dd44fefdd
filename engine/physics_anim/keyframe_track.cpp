#include "engine/physics_anim/keyframe_track.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/physics_anim/quat_interp.h"

namespace rtrt::physics {

namespace {

// The key at or before t (clamped to the ends) and the fraction of the way to the next one.
std::pair<size_t, float> Locate(const std::vector<float>& times, float t) {
    if (times.size() == 1 || t <= times.front()) return {0, 0.0f};
    if (t >= times.back()) return {times.size() - 1, 0.0f};
    const size_t k =
        static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    return {k, (t - times[k]) / (times[k + 1] - times[k])};
}

std::string ValidateTimes(const std::vector<float>& times, const char* name) {
    for (size_t i = 0; i < times.size(); ++i) {
        if (!std::isfinite(times[i]) || times[i] < 0.0f) {
            return std::string(name) + ": key time must be finite and >= 0 (key " +
                   std::to_string(i) + ")";
        }
        if (i > 0 && !(times[i] > times[i - 1])) {
            return std::string(name) + ": key times must increase strictly (key " +
                   std::to_string(i) + ")";
        }
    }
    return {};
}

// VALUES, and for a cubic track both tangent lists, hold `perKey` entries per key time.
std::string ValidateCounts(size_t keys, size_t perKey, size_t values, size_t in, size_t out,
                           bool cubic, const char* name, const char* what) {
    if (values != keys * perKey) {
        return std::string(name) + ": " + std::to_string(keys) + " key times but " +
               std::to_string(values) + " " + what;
    }
    if (cubic && (in != values || out != values)) {
        return std::string(name) + ": " + std::to_string(values) + " " + what + " but " +
               std::to_string(in) + " in-tangents and " + std::to_string(out) + " out-tangents";
    }
    return {};
}

template <typename T>
std::string ValidateTrack(const Track<T>& track, const char* name) {
    const bool cubic = track.interpolation == Interpolation::kCubicSpline;
    std::string error =
        ValidateCounts(track.times.size(), 1, track.values.size(), track.inTangents.size(),
                       track.outTangents.size(), cubic, name, "values");
    return error.empty() ? ValidateTimes(track.times, name) : error;
}

std::string ValidateWeights(const WeightsTrack& track) {
    if (track.Empty()) return {};
    if (track.count == 0) return "weights: a weights track needs at least one weight per key";
    const bool cubic = track.interpolation == Interpolation::kCubicSpline;
    std::string error = ValidateCounts(track.times.size(), track.count, track.values.size(),
                                       track.inTangents.size(), track.outTangents.size(), cubic,
                                       "weights", "weights");
    return error.empty() ? ValidateTimes(track.times, "weights") : error;
}

template <typename T>
T CubicSegment(const Track<T>& track, size_t k, float u) {
    const float td = track.times[k + 1] - track.times[k];
    return Hermite(track.values[k], track.outTangents[k], track.values[k + 1],
                   track.inTangents[k + 1], td, u);
}

}  // namespace

vec3 SampleTrack(const Vec3Track& track, float t) {
    const auto [k, u] = Locate(track.times, t);
    if (u == 0.0f || track.interpolation == Interpolation::kStep) return track.values[k];
    if (track.interpolation == Interpolation::kCubicSpline) return CubicSegment(track, k, u);
    return glm::mix(track.values[k], track.values[k + 1], u);
}

glm::quat SampleTrack(const QuatTrack& track, float t) {
    const auto [k, u] = Locate(track.times, t);
    if (u == 0.0f || track.interpolation == Interpolation::kStep) return track.values[k];
    if (track.interpolation == Interpolation::kCubicSpline) {
        // The spline runs through the keys' components as written (no shortest-way flip: the
        // tangents were authored for these signs); only its result is made a unit rotation.
        const glm::quat q = CubicSegment(track, k, u);
        const float length = glm::length(q);
        return length > 0.0f ? q / length : track.values[k];
    }
    if (track.interpolation == Interpolation::kLinear) {
        return Nlerp(track.values[k], track.values[k + 1], u);
    }
    return Slerp(track.values[k], track.values[k + 1], u);
}

void SampleTrack(const WeightsTrack& track, float t, std::span<float> weights) {
    const auto [k, u] = Locate(track.times, t);
    const size_t n = track.count, at = k * n;
    if (u == 0.0f || track.interpolation == Interpolation::kStep) {
        std::copy_n(track.values.begin() + std::ptrdiff_t(at), n, weights.begin());
        return;
    }
    const float td = track.times[k + 1] - track.times[k];
    for (size_t i = 0; i < n; ++i) {
        const float v0 = track.values[at + i], v1 = track.values[at + n + i];
        weights[i] =
            track.interpolation == Interpolation::kCubicSpline
                ? Hermite(v0, track.outTangents[at + i], v1, track.inTangents[at + n + i], td, u)
                : v0 + (v1 - v0) * u;
    }
}

float KeyframeClip::Duration() const {
    float duration = 0.0f;
    if (!translation.Empty()) duration = std::max(duration, translation.times.back());
    if (!rotation.Empty()) duration = std::max(duration, rotation.times.back());
    if (!scale.Empty()) duration = std::max(duration, scale.times.back());
    if (!weights.Empty()) duration = std::max(duration, weights.times.back());
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
    if (error.empty()) error = ValidateWeights(clip.weights);
    return error;
}

}  // namespace rtrt::physics
