#pragma once
// Keyframe tracks for translation, rotation, scale and morph weights, and a clip that bundles
// them.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

// How a track fills the time between two keys. kSlerp is meant for rotation tracks; on a vec3
// track it is the same as kLinear. kLinear on a rotation track is a shortest-path Nlerp.
// kCubicSpline is glTF's CUBICSPLINE: a cubic Hermite spline through the keys with the track's
// own tangents (inTangents, outTangents); a rotation is normalised after, as glTF says.
enum class Interpolation : uint8_t { kStep, kLinear, kSlerp, kCubicSpline };

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
    // kCubicSpline only, one per key (glTF's a_k and b_k, per second): the tangent arriving at
    // and the one leaving each key. The first key's in-tangent and the last one's out-tangent
    // shape nothing.
    std::vector<T> inTangents, outTangents;

    bool Empty() const { return times.empty(); }
};
using Vec3Track = Track<vec3>;
using QuatTrack = Track<glm::quat>;

// Morph target weights: `count` weights per key, key-major (key k's are [k * count,
// (k + 1) * count)), and so are the tangents of a kCubicSpline track. kSlerp is kLinear here.
struct WeightsTrack {
    uint32_t count = 0;
    std::vector<float> times;
    std::vector<float> values;
    Interpolation interpolation = Interpolation::kLinear;
    std::vector<float> inTangents, outTangents;

    bool Empty() const { return times.empty(); }
};

// The value at time t. The track must be non-empty and valid (ValidateClip).
vec3 SampleTrack(const Vec3Track& track, float t);
glm::quat SampleTrack(const QuatTrack& track, float t);
// Writes the track's `count` weights at time t into weights (which must hold count).
void SampleTrack(const WeightsTrack& track, float t, std::span<float> weights);

// glTF 2.0, Appendix C: the cubic Hermite segment from value v0 (out-tangent b0) to v1
// (in-tangent a1) over a key interval of td seconds, at fraction u of the way.
template <typename T>
T Hermite(const T& v0, const T& b0, const T& v1, const T& a1, float td, float u) {
    const float u2 = u * u, u3 = u2 * u;
    return (2.0f * u3 - 3.0f * u2 + 1.0f) * v0 + (td * (u3 - 2.0f * u2 + u)) * b0 +
           (-2.0f * u3 + 3.0f * u2) * v1 + (td * (u3 - u2)) * a1;
}

// A clip's time runs from 0 to Duration(), the latest key of its tracks. A channel without keys
// is left as the pose had it, so a clip can animate rotation alone. The weights channel poses
// the morph targets of the entity's mesh (MorphWeights, skinning.h), not its transform.
struct KeyframeClip {
    Vec3Track translation;
    QuatTrack rotation;
    Vec3Track scale;
    WeightsTrack weights;
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
