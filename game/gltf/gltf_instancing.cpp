// Placing a glTF asset in a scene (InstantiateGltf, gltf_import.h): its nodes as entities, its
// lights and first camera at their world poses.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <string>

#include "engine/core/error.h"
#include "game/gltf/gltf_import.h"

namespace rtrt {
namespace {

// v's direction, scaled by its largest component first so that neither a huge nor a tiny
// (but finite) vector overflows or underflows on the way; zero for a zero vector.
vec3 UnitDirection(vec3 v) {
    const float largest = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    if (!(largest > 0.0f)) return vec3(0.0f);
    return glm::normalize(v / largest);
}

bool AllFinite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// What makes primitive PRIM of node NODE deform in this instance: its skin, whose joints are
// this instance's entities of the joint nodes (ENTITY: each node's entity index), and its
// morph weights, played by its node's animator.
void Deforming(const GltfAsset& asset, size_t node, const GltfPrimitive& prim,
               const std::vector<int32_t>& entity, double phase, const LoadedScene& out,
               EntityDesc& p) {
    const GltfNode& n = asset.nodes[node];
    const DeformableMesh& mesh = *out.scene.deformableMeshes[size_t(prim.deformableMesh)];
    p.deformableMesh = prim.deformableMesh;
    if (mesh.Skinned() && n.skin >= 0 && !asset.skins[size_t(n.skin)].joints.empty()) {
        const GltfSkin& skin = asset.skins[size_t(n.skin)];
        EntityDesc::SkinDesc s;
        for (int32_t joint : skin.joints) s.joints.push_back(entity[size_t(joint)]);
        s.inverseBind = skin.inverseBind;
        if (prim.nodeJoint) {  // unweighted vertices follow this very entity: an identity joint
            s.joints.push_back(int32_t(out.entities.size()));
            s.inverseBind.push_back(glm::mat4(1.0f));
        }
        p.skin = std::move(s);
    }
    if (mesh.targetCount > 0) {
        EntityDesc::MorphDesc m;
        m.weights = n.morphWeights;
        if (n.clip && !n.clip->weights.Empty() && n.clip->weights.count == m.weights.size()) {
            m.animator = entity[node];
            physics::SampleTrack(n.clip->weights, physics::ClipTime(*n.clip, phase), m.weights);
        }
        p.morph = std::move(m);
    }
}

}  // namespace

std::optional<Camera> InstantiateGltf(const GltfAsset& asset, LoadedScene& out, int32_t parent,
                                      const glm::mat4& parentWorld, double phase) {
    std::optional<Camera> camera;
    // Each node's entity index, known before any is placed: a skin's joints can come after the
    // primitives they bend. A node's entity is followed by its primitives' entities.
    std::vector<int32_t> entity(asset.nodes.size());
    int32_t next = int32_t(out.entities.size());
    for (size_t i = 0; i < asset.nodes.size(); ++i) {
        entity[i] = next;
        next += 1 + int32_t(asset.nodes[i].primitives.size());
    }
    std::vector<glm::mat4> world(asset.nodes.size());
    for (size_t i = 0; i < asset.nodes.size(); ++i) {
        const GltfNode& node = asset.nodes[i];
        const int32_t up = node.parent >= 0 ? entity[size_t(node.parent)] : parent;
        EntityDesc e;
        e.renderable = false;
        e.parent = up;
        e.sourceArray = "nodes";
        e.sourceIndex = node.source;
        e.local = node.local;
        if (node.clip) {
            physics::Animator animator;
            animator.clip = node.clip;
            animator.base = node.local;
            animator.time = phase;
            e.animator = animator;
            e.local = physics::EvaluateAnimator(animator);  // posed at its phase, also at 0
        }
        // Cameras and lights are placed where the animation has their nodes when the scene
        // starts, as the meshes are (they do not follow it afterwards).
        world[i] = (node.parent >= 0 ? world[size_t(node.parent)] : parentWorld) *
                   physics::ToMatrix(e.local);
        out.entities.push_back(e);
        for (const GltfPrimitive& prim : node.primitives) {
            EntityDesc p;
            p.blasId = prim.blas;
            p.materialId = prim.material;
            p.parent = entity[i];
            p.sourceArray = "nodes";
            p.sourceIndex = node.source;
            if (prim.deformableMesh >= 0) Deforming(asset, i, prim, entity, phase, out, p);
            out.entities.push_back(p);
        }
        const vec3 origin = vec3(world[i] * glm::vec4(0, 0, 0, 1));
        // Nodes that shade or view the scene from their world transform: values each within
        // range can still multiply past a float's.
        const bool placed = AllFinite(world[i]);
        if ((node.light >= 0 || node.camera >= 0) && !placed)
            throw InputError(asset.summary.file, "nodes[" + std::to_string(node.source) + "]",
                             std::string("its world transform overflows a float (the product of "
                                         "its ancestors' transforms); the ") +
                                 (node.light >= 0 ? "light" : "camera") +
                                 " on it would have no place");
        if (node.light >= 0) {
            const GltfLight& l = asset.lights[size_t(node.light)];
            Light light;
            light.type = l.type;
            light.color = l.color;
            // Lights shine along the node's -z: the direction toward a directional one is +z.
            const vec3 toward = UnitDirection(vec3(world[i] * glm::vec4(0, 0, 1, 0)));
            const vec3 unitToward = toward != vec3(0.0f) ? toward : vec3(0, 0, 1);  // scale 0
            if (l.type == LightType::kDirectional) {
                light.vector = unitToward;
            } else {
                light.vector = origin;
                light.falloff = 1;
                light.range = l.range;
                light.spotAxis = -unitToward;
                if (l.type == LightType::kSpot) SetSpotCone(&light, l.innerCone, l.outerCone);
            }
            out.scene.lights.push_back(light);
        }
        if (node.camera >= 0 && !camera) {
            Camera c;
            c.position = origin;
            c.forward = UnitDirection(vec3(world[i] * glm::vec4(0, 0, -1, 0)));
            c.up = UnitDirection(vec3(world[i] * glm::vec4(0, 1, 0, 0)));
            c.fovYDegrees = asset.cameras[size_t(node.camera)].fovYDegrees;
            if (glm::length(glm::cross(c.forward, c.up)) > 0.0f) camera = c;
        }
    }
    return camera;
}

}  // namespace rtrt
