#pragma once
// Keyframe tracks for translation, rotation and scale, and a clip that bundles the three.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

// How a track fills the time between two keys. kSlerp is meant for rotation tracks; on a vec3
// track it is the same as kLinear. kLinear on a rotation track is a shortest-path Nlerp.
enum class Interpolation : uint8_t { kStep, kLinear, kSlerp };

// What a clip does past its last key: kClamp holds the last (and before 0 the first) pose; kLoop
// plays the clip again from time 0, with period Duration().
enum class WrapMode : uint8_t { kClamp, kLoop };

// Keys at strictly increasing times (seconds), one value per time. Outside [first, last] key time
// a track holds its end values.
template <typename T>
struct Track {
    std::vector<float> times;
    std::vector<T> values;
    Interpolation interpolation = Interpolation::kLinear;

    bool Empty() const { return times.empty(); }
};
using Vec3Track = Track<vec3>;
using QuatTrack = Track<glm::quat>;

// The value at time t. The track must be non-empty and valid (ValidateClip).
vec3 SampleTrack(const Vec3Track& track, float t);
glm::quat SampleTrack(const QuatTrack& track, float t);

// A clip's time runs from 0 to Duration(), the latest key of its tracks. A channel without keys
// is left as the pose had it, so a clip can animate rotation alone.
struct KeyframeClip {
    Vec3Track translation;
    QuatTrack rotation;
    Vec3Track scale;
    WrapMode wrap = WrapMode::kClamp;

    float Duration() const;
};

// Maps an animation time onto the clip's [0, Duration()] according to its wrap mode.
float ClipTime(const KeyframeClip& clip, double time);
// Overwrites the channels of pose that the clip has keys for with their value at time.
void SampleClip(const KeyframeClip& clip, double time, LocalTransform& pose);

// Empty when the clip is usable; otherwise what is wrong and in which track, e.g.
// "rotation: key times must increase strictly (key 3)".
std::string ValidateClip(const KeyframeClip& clip);

}  // namespace rtrt::physics
