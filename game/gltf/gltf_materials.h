#pragma once
// glTF materials as rtrt's PBR materials with their textures (and a Blinn-Phong approximation
// for kernels without PBR), each added to the scene once however many primitives use it.
#include <cstdint>
#include <map>
#include <string>

#include "game/gltf/gltf_document.h"
#include "game/gltf/gltf_textures.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

// The Blinn-Phong approximation's ambient: the PBR material's ambient light on its diffuse
// colour, plus its emission.
inline vec3 GltfApproximationAmbient(const PbrMaterial& p) {
    return p.ambientLight * p.baseColor * (1.0f - p.metallic) + p.emissive;
}

class GltfMaterials {
  public:
    GltfMaterials(GltfDocument& doc, LoadedScene& out)
        : doc_(doc), model_(doc.Model()), out_(out), textures_(doc, out) {}

    // The scene's material for glTF material INDEX (-1: a default grey), which FIELD refers to.
    uint32_t Id(int index, const std::string& field);

  private:
    // The texture record of KEY in material G's EXTENSION (kNoTexture where absent).
    uint32_t ExtensionSlot(const tinygltf::Material& g, const std::string& at,
                           const char* extension, const char* key, bool srgb,
                           TexelChannels channels = TexelChannels::kRgb);

    GltfDocument& doc_;
    const tinygltf::Model& model_;
    LoadedScene& out_;
    GltfTextures textures_;
    std::map<int, uint32_t> materialIds_;
    uint32_t defaultMaterial_ = UINT32_MAX;
};

}  // namespace rtrt
