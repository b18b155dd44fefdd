#pragma once
// glTF animation: node translation, rotation, scale and morph weights channels as keyframe clips.
#include <cstdint>
#include <vector>

#include "game/gltf/gltf_asset.h"
#include "game/gltf/gltf_document.h"

namespace rtrt {

// The first animation's translation, rotation, scale and weights channels as per-node keyframe
// clips (STEP, LINEAR and CUBICSPLINE as the specification defines them),
// looping over the animation's duration.
// NODESLOT maps glTF nodes to asset.nodes (ReadGltfNodes); channels of nodes outside the scene
// shown are dropped.
void ReadGltfAnimation(GltfDocument& doc, const std::vector<int32_t>& nodeSlot, GltfAsset& asset);

}  // namespace rtrt
