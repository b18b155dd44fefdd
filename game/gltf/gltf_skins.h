#pragma once
// glTF skins: their joints as nodes of the scene shown and their inverse bind matrices.
#include <cstdint>
#include <vector>

#include "game/gltf/gltf_asset.h"
#include "game/gltf/gltf_document.h"

namespace rtrt {

// Throws InputError for a skin without joints or with a node listed twice among them: checked
// before the meshes, whose joint indices are read against their skin's joint count.
void CheckGltfSkinJoints(const GltfDocument& doc);

// The file's skins into asset.skins (by index), their joints mapped through NODESLOT
// (ReadGltfNodes). Throws InputError for a joint out of range or outside
// the scene shown, or inverse bind matrices that are not finite float 4x4s, one per joint.
void ReadGltfSkins(GltfDocument& doc, const std::vector<int32_t>& nodeSlot, GltfAsset& asset);

}  // namespace rtrt
