#include "game/scene/loaded_scene.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "engine/core/error.h"
#include "engine/physics_anim/animator.h"
#include "engine/physics_anim/skinning.h"

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

namespace {

// The entities in the order they appear (the runtime spawns them front to back), those of one
// time as loaded. Their links to one another (parents, skin joints, the animator of morph
// weights) are indices, renumbered with them: a glTF spawner's node tree listed after a later
// spawner moves past that one's bodies.
void SortBySpawnTime(std::vector<EntityDesc>& entities) {
    std::vector<uint32_t> order(entities.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return entities[a].spawnTime < entities[b].spawnTime;
    });
    std::vector<int32_t> newIndex(entities.size());
    for (size_t at = 0; at < order.size(); ++at) newIndex[order[at]] = int32_t(at);
    auto renumber = [&](int32_t& index) {
        if (index >= 0) index = newIndex[size_t(index)];
    };
    std::vector<EntityDesc> sorted;
    sorted.reserve(entities.size());
    for (const uint32_t from : order) {
        EntityDesc& e = sorted.emplace_back(std::move(entities[from]));
        renumber(e.parent);
        if (e.skin)
            for (int32_t& joint : e.skin->joints) renumber(joint);
        if (e.morph) renumber(e.morph->animator);
        // A parent appears with its children or before them, so it still comes first.
        if (e.parent >= int32_t(sorted.size()) - 1)
            throw std::logic_error("FinishLoadedScene: an entity appears before its parent");
    }
    entities = std::move(sorted);
}

}  // namespace

void FinishLoadedScene(LoadedScene& out, const std::string& file) {
    SortBySpawnTime(out.entities);
    // An animated entity starts posed at its animation's time 0 (the runtime advances the clock
    // before it poses again): its own "position" showed in the first frame, and the second
    // jumped to the animation (demo_glass's orbiting ball).
    for (EntityDesc& e : out.entities)
        if (e.animator) e.local = physics::EvaluateAnimator(*e.animator);
    const std::vector<glm::mat4> worlds = InitialWorlds(out);
    for (size_t i = 0; i < out.entities.size(); ++i) {
        const EntityDesc& e = out.entities[i];
        // A skinned mesh is placed as the runtime places it (skinning.h).
        const glm::mat4 placement = e.skin ? physics::SkinnedMeshFrame(worlds[i]) : worlds[i];
        if (e.renderable) {
            const Aabb b = out.scene.blases[e.blasId]->bounds;
            for (int corner = 0; corner < 8; ++corner) {
                const vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                             (corner & 4) ? b.max.z : b.min.z);
                const glm::vec4 w = placement * glm::vec4(p, 1.0f);
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
            out.scene.AddInstance(e.blasId, e.materialId, placement);
    }
    out.dynamic |= !out.cameraPath.empty();
    if (!out.cameraPath.empty()) out.scene.camera = CameraAt(out, 0.0);
    out.scene.BuildTlas();
}

Camera CameraAt(const LoadedScene& loaded, double t) {
    Camera camera = loaded.scene.camera;
    const std::vector<CameraKey>& path = loaded.cameraPath;
    if (path.empty()) return camera;
    size_t next = 0;
    while (next < path.size() && path[next].time <= t) ++next;
    const CameraKey& a = path[next == 0 ? 0 : next - 1];
    const CameraKey& b = path[next == path.size() ? path.size() - 1 : next];
    // In double: a float clock moves in steps of a frame or more past 131072 s at 60 fps.
    const double span = double(b.time) - double(a.time);
    const float w = span > 0.0 ? float(std::clamp((t - a.time) / span, 0.0, 1.0)) : 0.0f;
    camera.position = glm::mix(a.position, b.position, w);
    camera.forward = ScaledForNormalize(glm::mix(a.lookAt, b.lookAt, w) - camera.position);
    return camera;
}

}  // namespace rtrt
