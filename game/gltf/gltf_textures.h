#pragma once
// The textures a glTF material's slots name, decoded once per image and recorded once per
// (image, colour encoding, KHR_texture_transform) in the scene's texture table.
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "game/gltf/gltf_document.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

// A material's reference to a texture, whatever its slot (tinygltf keeps three types of them).
struct GltfTextureRef {
    int index = -1;
    int texCoord = 0;
    const tinygltf::ExtensionMap* extensions = nullptr;
};

// Which of an image's channels a slot samples: its colour, or its alpha recorded as grey (the
// renderer samples colour alone; KHR_materials_specular keeps its strength in alpha).
enum class TexelChannels { kRgb, kAlphaAsGrey };

class GltfTextures {
  public:
    GltfTextures(GltfDocument& doc, LoadedScene& out) : doc_(doc), model_(doc.Model()), out_(out) {}

    // The scene's texture record for ref, found at field `at`, or kNoTexture where the slot is
    // empty or rtrt cannot use it (with a warning). srgb: the texels are sRGB-encoded colours.
    uint32_t Slot(const GltfTextureRef& ref, const std::string& at, bool srgb,
                  TexelChannels channels = TexelChannels::kRgb);

  private:
    // The texture's texels in the scene with their mip levels (averaged in linear light where
    // srgb), decoded at its first use: the record without transform.
    const Texture* Decoded(int index, bool srgb, TexelChannels channels, const std::string& at);
    bool ReadTransform(const GltfTextureRef& ref, const std::string& at, Texture* texture);

    GltfDocument& doc_;
    const tinygltf::Model& model_;
    LoadedScene& out_;
    // By texture index, srgb and channels; 0 x 0: unusable.
    std::map<std::tuple<int, bool, TexelChannels>, Texture> decoded_;
    // Image, srgb, levels, channels: offset.
    std::map<std::tuple<int, bool, uint32_t, TexelChannels>, uint64_t> texels_;
    std::map<std::tuple<int, bool, TexelChannels, std::vector<float>>, uint32_t> records_;
};

}  // namespace rtrt
