#include "game/scene/scene_camera_path.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/render_rt/camera.h"

namespace rtrt {
namespace {

// Whether the view direction, interpolated linearly from key A to key B as CameraAt does
// (look_at(w) - position(w) = F + w G), passes through zero or comes parallel to UP on the
// way. Both are found in closed form: the view's length is smallest where w = -F.G / G.G,
// and its part across UP, cross(F + w G, up), is linear in w too. A view at least 1e-6 of
// the keys' views long whose part across up is at least 1e-6 of its length has a basis
// (the keys themselves are checked on their own).
bool PathTurnsParallelToUp(const CameraKey& a, const CameraKey& b, vec3 up) {
    const glm::dvec3 u = glm::normalize(glm::dvec3(ScaledForNormalize(up)));
    const glm::dvec3 fa = glm::dvec3(a.lookAt) - glm::dvec3(a.position);
    const glm::dvec3 fb = glm::dvec3(b.lookAt) - glm::dvec3(b.position);
    const glm::dvec3 g = fb - fa;
    auto smallestAt = [](glm::dvec3 from, glm::dvec3 step) {
        const double stepSquared = glm::dot(step, step);
        return stepSquared > 0.0 ? std::clamp(-glm::dot(from, step) / stepSquared, 0.0, 1.0) : 0.0;
    };
    const double keys = std::max(glm::length(fa), glm::length(fb));
    if (glm::length(fa + smallestAt(fa, g) * g) <= 1e-6 * keys) return true;
    const glm::dvec3 side = glm::cross(fa, u), turn = glm::cross(g, u);
    const double w = smallestAt(side, turn);
    return glm::length(side + w * turn) < 1e-6 * glm::length(fa + w * g);
}

}  // namespace

std::vector<CameraKey> ParseCameraPath(const Json& j, vec3 up, const std::string& file) {
    if (!j.is_array() || j.empty())
        throw InputError(file, "camera_path", "expected a non-empty array of camera keys");
    std::vector<CameraKey> path;
    for (size_t i = 0; i < j.size(); ++i) {
        JsonFields f(j[i], JsonIndexed("camera_path", i), file);
        CameraKey key;
        key.time = f.InRange("time", 0.0f, 1e6f, 0.0f);
        key.position = f.Position("position");
        key.lookAt = f.Vec3("look_at");
        f.Finish();
        if (!path.empty() && key.time <= path.back().time)
            f.Fail("time", "camera keys must come in increasing time");
        if (key.position == key.lookAt) f.Fail("look_at", "must differ from position");
        if (!IsFinite(key.lookAt - key.position))
            f.Fail("look_at",
                   "the view direction is beyond float's range (look_at too far from position)");
        if (!CameraBasisDefined(key.lookAt - key.position, up))
            f.Fail("look_at",
                   "the view direction is parallel to the camera's up (camera.up, default [0, 1, "
                   "0]): give the camera another up");
        if (!path.empty() && PathTurnsParallelToUp(path.back(), key, up))
            f.Fail("look_at",
                   "on the way from the key before, the view direction turns parallel to the "
                   "camera's up (camera.up, default [0, 1, 0]) or look_at passes through "
                   "position: add a key between them or give the camera another up");
        path.push_back(key);
    }
    return path;
}

}  // namespace rtrt
