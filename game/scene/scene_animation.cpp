#include "game/scene/scene_animation.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <memory>

#include "engine/core/math.h"

namespace rtrt {
namespace {

vec3 NonZero(JsonFields& f, const std::string& key, vec3 fallback) {
    // Scaled first: the squared length of [1e20, 0, 0] overflows and of [1e-30, 0, 0] underflows.
    const vec3 v = ScaledForNormalize(f.Vec3(key, fallback));
    if (v == vec3(0.0f)) f.Fail(key, "must not be the zero vector");
    return glm::normalize(v);
}

// keyframes: {"translation": [[t, x, y, z], ...], "rotation": [[t, degrees x, y, z], ...],
// "scale": [[t, x, y, z], ...], "interpolation": "step" | "linear" | "slerp", "loop": bool}.
// The clip sets the channels it has keys for; the motions apply after it.
std::shared_ptr<const physics::KeyframeClip> ParseClip(const Json& j, const std::string& path,
                                                       const std::string& file) {
    JsonFields f(j, path, file);
    auto clip = std::make_shared<physics::KeyframeClip>();
    physics::Interpolation mode = physics::Interpolation::kLinear;
    const std::string interpolation = f.String("interpolation", "linear");
    if (interpolation == "step")
        mode = physics::Interpolation::kStep;
    else if (interpolation == "slerp")
        mode = physics::Interpolation::kSlerp;
    else if (interpolation != "linear")
        f.Fail("interpolation", "expected step, linear or slerp, got \"" + interpolation + "\"");
    if (f.Has("loop")) {
        if (!f.Get("loop").is_boolean()) f.Fail("loop", "expected true or false");
        clip->wrap =
            f.Get("loop").get<bool>() ? physics::WrapMode::kLoop : physics::WrapMode::kClamp;
    }
    auto keys = [&](const std::string& channel, auto&& add) {
        if (!f.Has(channel)) return;
        const Json& list = f.Get(channel);
        if (!list.is_array() || list.empty())
            f.Fail(channel, "expected a non-empty array of [time, x, y, z]");
        for (size_t k = 0; k < list.size(); ++k) {
            const Json& key = list[k];
            const std::string at = channel + "[" + std::to_string(k) + "]";
            if (!key.is_array() || key.size() != 4) f.Fail(at, "expected [time, x, y, z]");
            for (const Json& v : key)
                if (!v.is_number() || !(std::fabs(v.get<double>()) <= 3.4e38))
                    f.Fail(at, "expected numbers within float's range (at most 3.4e38)");
            // A clip is sampled in float: beyond 1e6 s its keys are seconds apart in a float.
            if (!(std::fabs(key[0].get<double>()) <= 1e6))
                f.Fail(at,
                       "key times must be at most 1e6 seconds in magnitude, as the scene's "
                       "other times");
            add(at, key[0].get<float>(),
                vec3(key[1].get<float>(), key[2].get<float>(), key[3].get<float>()));
        }
    };
    // Poses within what the scene's own fields allow (positions, scales), and angles a float
    // turns precisely: a key of 1e20 or a scale of 1e30 made the object vanish.
    const auto within = [&](const std::string& at, vec3 v, float lo, float hi, const char* rule) {
        if (!(std::min({v.x, v.y, v.z}) >= lo && std::max({v.x, v.y, v.z}) <= hi)) f.Fail(at, rule);
    };
    keys("translation", [&](const std::string& at, float t, vec3 v) {
        within(at, v, -kMaxSceneCoordinate, kMaxSceneCoordinate,
               "coordinates must be at most 1e7 in magnitude");
        clip->translation.times.push_back(t);
        clip->translation.values.push_back(v);
    });
    keys("rotation", [&](const std::string& at, float t, vec3 degrees) {
        within(at, degrees, -1e6f, 1e6f, "angles must be at most 1e6 degrees in magnitude");
        clip->rotation.times.push_back(t);
        clip->rotation.values.push_back(EulerDegrees(degrees));
    });
    keys("scale", [&](const std::string& at, float t, vec3 v) {
        within(at, v, 1e-6f, 1e6f,
               "scale factors must be between 1e-6 and 1e6 (a pop-in starts at 1e-6: a scale of 0 "
               "has no inverse to trace with)");
        // As an instance's scale (scene_file.cpp): flattened further, a model no longer traces.
        if (!(std::min({v.x, v.y, v.z}) >= 1e-4f * std::max({v.x, v.y, v.z})))
            f.Fail(at, "the smallest scale factor must be at least 1e-4 of the largest");
        clip->scale.times.push_back(t);
        clip->scale.values.push_back(v);
    });
    clip->translation.interpolation = clip->scale.interpolation = mode;
    clip->rotation.interpolation =
        mode == physics::Interpolation::kLinear ? physics::Interpolation::kSlerp : mode;
    f.Finish();
    if (clip->translation.Empty() && clip->rotation.Empty() && clip->scale.Empty())
        f.Fail("", "give keys for at least one of translation, rotation, scale");
    if (const std::string problem = physics::ValidateClip(*clip); !problem.empty())
        f.Fail("", problem);
    return clip;
}

}  // namespace

glm::quat EulerDegrees(vec3 degrees) {
    return glm::angleAxis(glm::radians(degrees.z), vec3(0, 0, 1)) *
           glm::angleAxis(glm::radians(degrees.y), vec3(0, 1, 0)) *
           glm::angleAxis(glm::radians(degrees.x), vec3(1, 0, 0));
}

// Motions apply in a fixed order: orbit, then spin, then bob.
physics::Animator ParseAnimator(const Json& j, const std::string& path,
                                const physics::LocalTransform& base, const std::string& file) {
    JsonFields f(j, path, file);
    physics::Animator a;
    a.base = base;
    if (f.Has("orbit")) {
        JsonFields o(f.Get("orbit"), f.Path("orbit"), file);
        physics::Orbit orbit;
        orbit.centre = o.Position("centre", base.translation);
        orbit.radius = o.InRange("radius", 1e-6f, kMaxSceneCoordinate, 1.0f);
        orbit.axis = NonZero(o, "axis", vec3(0, 1, 0));
        orbit.period = o.Positive("period", 4.0f);
        o.Finish();
        a.motions.push_back(orbit);
    }
    if (f.Has("spin")) {
        JsonFields sp(f.Get("spin"), f.Path("spin"), file);
        physics::Spin spin;
        spin.axis = NonZero(sp, "axis", vec3(0, 1, 0));
        spin.angularSpeed = sp.Number("speed", 1.0f);
        sp.Finish();
        a.motions.push_back(spin);
    }
    if (f.Has("bob")) {
        JsonFields b(f.Get("bob"), f.Path("bob"), file);
        physics::Bob bob;
        bob.amplitude = b.InRange("amplitude", -kMaxSceneCoordinate, kMaxSceneCoordinate, 0.25f);
        bob.frequency = b.Positive("frequency", 0.5f);
        bob.axis = NonZero(b, "axis", vec3(0, 1, 0));
        b.Finish();
        a.motions.push_back(bob);
    }
    if (f.Has("keyframes")) a.clip = ParseClip(f.Get("keyframes"), f.Path("keyframes"), file);
    // An orbit sets the position outright, so translation keys under it would do nothing.
    if (f.Has("orbit") && a.clip && !a.clip->translation.Empty())
        f.Fail("orbit",
               "an orbit places the object itself: give translation keys or an orbit, "
               "not both");
    f.Finish();
    if (a.motions.empty() && !a.clip)
        f.Fail("", "give at least one of keyframes, orbit, spin, bob");
    return a;
}

}  // namespace rtrt
