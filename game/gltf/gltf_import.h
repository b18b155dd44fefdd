#pragma once
// glTF 2.0 files (.gltf with its buffers and images, or .glb) through tinygltf: meshes become
// BLASes (one per triangle primitive), materials rtrt's Blinn-Phong (the mapping is in the
// README), base-colour images textures, the node hierarchy entities with transforms, node TRS
// animations keyframe clips, KHR_lights_punctual lights rtrt lights, and the first perspective
// camera rtrt's camera. What rtrt does not support gets one warning each on stderr.
#include <memory>
#include <optional>
#include <string>
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

// True when PATH ends in .gltf or .glb (any case).
bool IsGltfPath(const std::string& path);

// Reads PATH and adds its BLASes, materials and textures to `scene` (names to the name lists).
// Throws InputError (file, field, reason) for a malformed file: a bad GLB header, JSON that is not
// glTF, accessors outside their buffers, non-finite values, indices out of range, node cycles,
// missing buffers or images.
GltfAsset LoadGltfAsset(const std::string& path, LoadedScene& out);

// Adds the asset's nodes as entities under entity `parent` (an index into out.entities, -1 for
// none) whose initial world matrix is parentWorld, and its lights, placed there, to the scene.
// Returns the first camera (in node order) placed the same way, if the file has one.
std::optional<Camera> InstantiateGltf(const GltfAsset& asset, LoadedScene& out, int32_t parent,
                                      const glm::mat4& parentWorld);

// A glTF file as a whole scene (rtrt render/play/info x.glb): its first camera, or one that
// frames the scene along -z; its lights, or one white directional light when it has none.
LoadedScene LoadGltfScene(const std::string& path);

}  // namespace rtrt
