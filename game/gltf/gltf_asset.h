#pragma once
// What a glTF file holds once read (gltf_import.h reads and places it): its nodes in parent-first
// order, skins, lights, cameras and what rtrt info reports.
#include <cstdint>
#include <memory>
#include <vector>

#include "game/scene/loaded_scene.h"

namespace rtrt {

// One triangle primitive of a node's mesh: its BLAS (the rest pose, for a deforming one) and
// material, and for a skinned or morphed primitive its RenderScene::deformableMeshes index.
struct GltfPrimitive {
    uint32_t blas = 0;
    uint32_t material = 0;
    int32_t deformableMesh = -1;
    // The mesh has vertices without skin weights: they follow an extra last joint, the
    // primitive's own entity, so that they stay put in its frame (ReadGltfSkinInfluences).
    bool nodeJoint = false;
};

// One node of a glTF scene, in an order where parents come before their children.
struct GltfNode {
    int32_t parent = -1;  // index into GltfAsset::nodes, or -1 for a root of the scene
    uint32_t source = 0;  // its index in the file's nodes
    physics::LocalTransform local;
    std::shared_ptr<const physics::KeyframeClip> clip;  // its channels of the played animation
    std::vector<GltfPrimitive> primitives;
    int32_t camera = -1;  // index into GltfAsset::cameras
    int32_t light = -1;   // index into GltfAsset::lights
    int32_t skin = -1;    // index into GltfAsset::skins, for its deforming primitives
    // The morph weights its mesh starts with (node.weights, else mesh.weights, else zeros); empty
    // when the mesh has no morph targets. The clip's weights track, if any, animates them.
    std::vector<float> morphWeights;
};

// A glTF skin: its joints (indices into GltfAsset::nodes) and their inverse bind matrices. A
// skin rtrt cannot use (a sparse inverseBindMatrices accessor) has no joints: what it skins keeps
// its rest pose.
struct GltfSkin {
    std::vector<int32_t> joints;
    std::vector<glm::mat4> inverseBind;  // one per joint; identity where the file gives none
    int32_t skeleton = -1;               // the file's skeleton root, if given (informative)
};

// A glTF light or camera in its node's frame (lights shine and cameras look along -z).
struct GltfLight {
    LightType type = LightType::kDirectional;
    vec3 color{1.0f};                          // lux (directional) or candela (point, spot)
    float range = 0.0f;                        // 0: unlimited
    float innerCone = 0.0f, outerCone = 0.0f;  // spot lights, radians
};
struct GltfCamera {
    float fovYDegrees = 45.0f;
    float aspect = 0.0f;  // 0: not given
};

// A glTF file's content, its BLASes, materials and textures already in a RenderScene; placing it
// (InstantiateGltf) adds entities and lights, as often as a scene file asks.
struct GltfAsset {
    std::vector<GltfNode> nodes;
    std::vector<GltfSkin> skins;  // by the file's skin index
    std::vector<GltfLight> lights;
    std::vector<GltfCamera> cameras;
    GltfSummary summary;
};

// The entities one placement of ASSET adds: one per node and one per primitive.
inline uint64_t GltfEntityCount(const GltfAsset& asset) {
    uint64_t count = 0;
    for (const GltfNode& node : asset.nodes) count += 1 + node.primitives.size();
    return count;
}

}  // namespace rtrt
