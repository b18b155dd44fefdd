#pragma once
// What a glTF file holds once read (gltf_import.h reads and places it): its nodes in parent-first
// order, lights, cameras and what rtrt info reports.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "game/scene/loaded_scene.h"

namespace rtrt {

// One node of a glTF scene, in an order where parents come before their children.
struct GltfNode {
    int32_t parent = -1;  // index into GltfAsset::nodes, or -1 for a root of the scene
    uint32_t source = 0;  // its index in the file's nodes
    physics::LocalTransform local;
    std::shared_ptr<const physics::KeyframeClip> clip;      // its channels of the played animation
    std::vector<std::pair<uint32_t, uint32_t>> primitives;  // (BLAS id, material id)
    int32_t camera = -1;                                    // index into GltfAsset::cameras
    int32_t light = -1;                                     // index into GltfAsset::lights
};

// A glTF light or camera in its node's frame (lights shine and cameras look along -z).
struct GltfLight {
    LightType type = LightType::kDirectional;
    vec3 color{1.0f};
};
struct GltfCamera {
    float fovYDegrees = 45.0f;
    float aspect = 0.0f;  // 0: not given
};

// A glTF file's content, its BLASes, materials and textures already in a RenderScene; placing it
// (InstantiateGltf) adds entities and lights, as often as a scene file asks.
struct GltfAsset {
    std::vector<GltfNode> nodes;
    std::vector<GltfLight> lights;
    std::vector<GltfCamera> cameras;
    GltfSummary summary;
};

}  // namespace rtrt
