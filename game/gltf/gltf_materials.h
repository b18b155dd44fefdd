#pragma once
// glTF materials and their base-colour textures, as rtrt's Blinn-Phong materials (the README's
// table says how), each added to the scene once however many primitives use it.
#include <cstdint>
#include <map>
#include <string>

#include "game/gltf/gltf_document.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

class GltfMaterials {
  public:
    GltfMaterials(GltfDocument& doc, LoadedScene& out)
        : doc_(doc), model_(doc.Model()), out_(out) {}

    // The scene's material for glTF material INDEX (-1: a default grey), which FIELD refers to.
    uint32_t Id(int index, const std::string& field);

  private:
    uint32_t BaseColorTexture(const tinygltf::TextureInfo& info, const std::string& materialAt);

    GltfDocument& doc_;
    const tinygltf::Model& model_;
    LoadedScene& out_;
    std::map<int, uint32_t> materialIds_, textureIds_;
    uint32_t defaultMaterial_ = UINT32_MAX;
};

}  // namespace rtrt
