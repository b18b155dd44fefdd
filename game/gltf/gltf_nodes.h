#pragma once
// glTF nodes: the hierarchy (checked to be a forest), node transforms, and the cameras and
// KHR_lights_punctual lights that nodes carry.
#include <cstdint>
#include <vector>

#include "game/gltf/gltf_asset.h"
#include "game/gltf/gltf_document.h"
#include "game/gltf/gltf_meshes.h"

namespace rtrt {

// The parent of every node (-1 for none). Throws InputError unless every node has at most one
// parent and none is its own ancestor, so that entities can be created parents first.
std::vector<int> CheckGltfNodeGraph(const GltfDocument& doc);

// The file's cameras and lights into asset.cameras and asset.lights, by index.
void ReadGltfCamerasAndLights(GltfDocument& doc, GltfAsset& asset);

// The nodes of the scene shown into asset.nodes, parents first, with their meshes' primitives.
// Returns, per glTF node, its index in asset.nodes (-1 for a node outside the scene shown).
std::vector<int32_t> ReadGltfNodes(GltfDocument& doc, const std::vector<int>& parentOf,
                                   GltfMeshes& meshes, GltfAsset& asset);

}  // namespace rtrt
