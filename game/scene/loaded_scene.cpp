#include "game/scene/loaded_scene.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/physics_anim/animator.h"

namespace rtrt {

std::vector<glm::mat4> InitialWorlds(const LoadedScene& out) {
    std::vector<glm::mat4> worlds(out.entities.size());
    for (size_t i = 0; i < out.entities.size(); ++i) {
        const EntityDesc& e = out.entities[i];
        const glm::mat4 local = physics::ToMatrix(e.local);
        worlds[i] = e.parent >= 0 ? worlds[size_t(e.parent)] * local : local;
    }
    return worlds;
}

void FinishLoadedScene(LoadedScene& out, const std::string& file) {
    // Entities with parents are all of time 0 and come before every spawner's, so the stable
    // sort moves none of them nor their parents.
    std::stable_sort(
        out.entities.begin(), out.entities.end(),
        [](const EntityDesc& a, const EntityDesc& b) { return a.spawnTime < b.spawnTime; });
    // An animated entity starts posed at its animation's time 0 (the runtime advances the clock
    // before it poses again): its own "position" showed in the first frame, and the second
    // jumped to the animation (demo_glass's orbiting ball).
    for (EntityDesc& e : out.entities)
        if (e.animator) e.local = physics::EvaluateAnimator(*e.animator);
    const std::vector<glm::mat4> worlds = InitialWorlds(out);
    for (size_t i = 0; i < out.entities.size(); ++i) {
        const EntityDesc& e = out.entities[i];
        if (e.renderable) {
            const Aabb b = out.scene.blases[e.blasId]->bounds;
            for (int corner = 0; corner < 8; ++corner) {
                const vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                             (corner & 4) ? b.max.z : b.min.z);
                const glm::vec4 w = worlds[i] * glm::vec4(p, 1.0f);
                if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z))
                    throw InputError(
                        file,
                        std::string(e.sourceArray) + "[" + std::to_string(e.sourceIndex) + "]",
                        "its world bounds are not finite (position, scale or model "
                        "size too large)");
            }
        }
        out.dynamic |= e.animator.has_value() || e.body.has_value() || e.spawnTime > 0.0f ||
                       e.deformableMesh >= 0;
        if (e.spawnTime == 0.0f && e.renderable)
            out.scene.AddInstance(e.blasId, e.materialId, worlds[i]);
    }
    out.dynamic |= !out.cameraPath.empty();
    if (!out.cameraPath.empty()) out.scene.camera = CameraAt(out, 0.0f);
    out.scene.BuildTlas();
}

Camera CameraAt(const LoadedScene& loaded, float t) {
    Camera camera = loaded.scene.camera;
    const std::vector<CameraKey>& path = loaded.cameraPath;
    if (path.empty()) return camera;
    size_t next = 0;
    while (next < path.size() && path[next].time <= t) ++next;
    const CameraKey& a = path[next == 0 ? 0 : next - 1];
    const CameraKey& b = path[next == path.size() ? path.size() - 1 : next];
    const float span = b.time - a.time;
    const float w = span > 0.0f ? std::clamp((t - a.time) / span, 0.0f, 1.0f) : 0.0f;
    camera.position = glm::mix(a.position, b.position, w);
    camera.forward = ScaledForNormalize(glm::mix(a.lookAt, b.lookAt, w) - camera.position);
    return camera;
}

}  // namespace rtrt
