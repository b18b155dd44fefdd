#include "game/gltf/gltf_materials.h"

#include <algorithm>
#include <filesystem>
#include <vector>

#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

TextureWrap Wrap(int mode) {
    if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::kClampToEdge;
    if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::kMirroredRepeat;
    return TextureWrap::kRepeat;
}

}  // namespace

// glTF's metallic-roughness material as rtrt's Blinn-Phong (the README's table says why).
uint32_t GltfMaterials::Id(int index, const std::string& field) {
    if (index < 0) {
        if (defaultMaterial_ == UINT32_MAX) {
            defaultMaterial_ = out_.scene.AddMaterial(Material{});
            out_.materialNames.push_back("(default grey)");
        }
        return defaultMaterial_;
    }
    if (size_t(index) >= model_.materials.size())
        doc_.Fail(field, "material " + std::to_string(index) + " out of range");
    auto found = materialIds_.find(index);
    if (found != materialIds_.end()) return found->second;
    const tinygltf::Material& g = model_.materials[size_t(index)];
    const std::string at = JsonIndexed("materials", size_t(index));
    const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
    auto number = [&](double v, const std::string& name, double lo, double hi) {
        if (!(v >= lo && v <= hi))
            doc_.Fail(at + "." + name,
                      "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
        return float(v);
    };
    auto colour = [&](const std::vector<double>& v, const std::string& name, vec3 fallback) {
        if (v.empty()) return fallback;
        if (v.size() < 3) doc_.Fail(at + "." + name, "expected 3 or 4 numbers");
        return vec3(number(v[0], name, 0, 1e6), number(v[1], name, 0, 1e6),
                    number(v[2], name, 0, 1e6));
    };
    auto extension = [&](const char* name, const char* key, double fallback) {
        auto it = g.extensions.find(name);
        if (it == g.extensions.end() || !it->second.Has(key)) return fallback;
        const tinygltf::Value& v = it->second.Get(key);
        if (!v.IsNumber()) doc_.Fail(at + ".extensions." + name + "." + key, "expected a number");
        return v.GetNumberAsDouble();
    };
    const vec3 base = colour(pbr.baseColorFactor, "pbrMetallicRoughness.baseColorFactor", vec3(1));
    const float metallic = number(pbr.metallicFactor, "pbrMetallicRoughness.metallicFactor", 0, 1);
    const float roughness =
        number(pbr.roughnessFactor, "pbrMetallicRoughness.roughnessFactor", 0, 1);
    const float transmission =
        number(extension("KHR_materials_transmission", "transmissionFactor", 0.0),
               "extensions.KHR_materials_transmission.transmissionFactor", 0, 1);
    const float ior = number(extension("KHR_materials_ior", "ior", 1.5),
                             "extensions.KHR_materials_ior.ior", 1, 10);
    const float specularFactor = number(extension("KHR_materials_specular", "specularFactor", 1.0),
                                        "extensions.KHR_materials_specular.specularFactor", 0, 1);
    vec3 specularColour(1.0f);
    if (auto it = g.extensions.find("KHR_materials_specular");
        it != g.extensions.end() && it->second.Has("specularColorFactor")) {
        const tinygltf::Value& v = it->second.Get("specularColorFactor");
        if (!v.IsArray() || v.ArrayLen() != 3)
            doc_.Fail(at + ".extensions.KHR_materials_specular.specularColorFactor",
                      "expected 3 numbers");
        for (int c = 0; c < 3; ++c) {
            if (!v.Get(c).IsNumber())
                doc_.Fail(at + ".extensions.KHR_materials_specular.specularColorFactor",
                          "expected 3 numbers");
            specularColour[c] =
                number(v.Get(c).GetNumberAsDouble(),
                       "extensions.KHR_materials_specular.specularColorFactor", 0, 1e6);
        }
    }
    const float strength =
        number(extension("KHR_materials_emissive_strength", "emissiveStrength", 1.0),
               "extensions.KHR_materials_emissive_strength.emissiveStrength", 0, 1e6);
    const vec3 emissive = colour(g.emissiveFactor, "emissiveFactor", vec3(0.0f)) * strength;
    for (const auto& [name, value] : g.extensions)
        if (name != "KHR_materials_transmission" && name != "KHR_materials_ior" &&
            name != "KHR_materials_specular" && name != "KHR_materials_emissive_strength")
            doc_.Warn("material:" + name,
                      at + ".extensions." + name + ": not supported; the material ignores it");
    if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty())
        doc_.Warn("alpha",
                  at + ".alphaMode: " + g.alphaMode + " is not supported; surfaces are opaque");
    if (g.normalTexture.index >= 0 || g.occlusionTexture.index >= 0 ||
        g.emissiveTexture.index >= 0 || pbr.metallicRoughnessTexture.index >= 0)
        doc_.Warn("textures", at + ": only base colour textures are supported; normal, "
                                   "occlusion, emissive and metallic-roughness textures are "
                                   "ignored");

    // Dielectric reflectance at normal incidence from the index of refraction, scaled by
    // KHR_materials_specular; metals reflect their base colour (the glTF BRDF's F0).
    const float f0Dielectric = ((ior - 1.0f) / (ior + 1.0f)) * ((ior - 1.0f) / (ior + 1.0f));
    const vec3 f0 = glm::mix(
        glm::min(vec3(f0Dielectric) * specularColour, vec3(1.0f)) * specularFactor, base, metallic);
    const float smooth = (1.0f - roughness) * (1.0f - roughness);
    Material m;
    m.diffuse = base * (1.0f - metallic) * (1.0f - transmission);
    m.ambient = 0.1f * base * (1.0f - metallic) + emissive;
    m.specular = f0;
    // Blinn-Phong exponent of the same highlight width as GGX of alpha = roughness^2
    // (Walter et al. 2007): n = 2 / alpha^2 - 2.
    const float alpha = std::max(roughness * roughness, 0.01f);
    m.shininess = std::clamp(2.0f / (alpha * alpha) - 2.0f, 1.0f, 10000.0f);
    m.transmissivity = transmission * (1.0f - metallic);
    m.reflectivity =
        std::min(std::max(std::max(f0.x, f0.y), f0.z) * smooth, 1.0f - m.transmissivity);
    m.ior = ior;
    m.baseColorTexture = BaseColorTexture(pbr.baseColorTexture, at);
    const uint32_t id = out_.scene.AddMaterial(m);
    out_.materialNames.push_back(
        g.name.empty() ? fs::path(doc_.File()).filename().string() + " " + at : g.name);
    materialIds_[index] = id;
    return id;
}

uint32_t GltfMaterials::BaseColorTexture(const tinygltf::TextureInfo& info,
                                         const std::string& materialAt) {
    if (info.index < 0) return kNoTexture;
    const std::string at = materialAt + ".pbrMetallicRoughness.baseColorTexture";
    if (size_t(info.index) >= model_.textures.size())
        doc_.Fail(at + ".index", "texture " + std::to_string(info.index) + " out of range");
    if (info.texCoord != 0) {
        doc_.Warn("texcoord", at + ".texCoord: only TEXCOORD_0 is supported; untextured");
        return kNoTexture;
    }
    if (info.extensions.count("KHR_texture_transform"))
        doc_.Warn("transform", at + ": KHR_texture_transform is ignored (textures are sampled "
                                    "at the primitive's own coordinates)");
    auto found = textureIds_.find(info.index);
    if (found != textureIds_.end()) return found->second;
    const tinygltf::Texture& t = model_.textures[size_t(info.index)];
    const std::string textureAt = JsonIndexed("textures", size_t(info.index));
    if (t.source < 0) {
        doc_.Warn("texture-source", textureAt +
                                        ": no image rtrt can read (an extension's "
                                        "format?); untextured");
        return textureIds_[info.index] = kNoTexture;
    }
    if (size_t(t.source) >= model_.images.size())
        doc_.Fail(textureAt + ".source", "image " + std::to_string(t.source) + " out of range");
    const tinygltf::Image& image = model_.images[size_t(t.source)];
    const std::string imageAt = JsonIndexed("images", size_t(t.source));
    const int channels = image.component, bytes = image.bits / 8;
    if (image.width <= 0 || image.height <= 0 || channels < 1 || channels > 4 ||
        (bytes != 1 && bytes != 2) ||
        image.image.size() !=
            size_t(image.width) * size_t(image.height) * size_t(channels) * size_t(bytes))
        doc_.Fail(imageAt, "the image is missing or could not be decoded");
    std::vector<uint32_t> rgba(size_t(image.width) * size_t(image.height));
    for (size_t p = 0; p < rgba.size(); ++p) {
        uint32_t c[4] = {0, 0, 0, 255};
        for (int k = 0; k < channels; ++k) {
            // 16-bit images keep their high byte, little-endian as stb and OIIO return them.
            c[k] =
                image.image[(p * size_t(channels) + size_t(k)) * size_t(bytes) + size_t(bytes - 1)];
        }
        if (channels <= 2) c[1] = c[2] = c[0];  // grey (and alpha)
        rgba[p] = c[0] | (c[1] << 8) | (c[2] << 16) | (c[3] << 24);
    }
    Texture texture;
    texture.width = uint32_t(image.width);
    texture.height = uint32_t(image.height);
    texture.srgb = 1;  // base colour textures are sRGB-encoded (glTF); scene files may say not
    if (t.sampler >= 0) {
        if (size_t(t.sampler) >= model_.samplers.size())
            doc_.Fail(textureAt + ".sampler",
                      "sampler " + std::to_string(t.sampler) + " out of range");
        const tinygltf::Sampler& s = model_.samplers[size_t(t.sampler)];
        texture.wrapS = Wrap(s.wrapS);
        texture.wrapT = Wrap(s.wrapT);
        texture.filter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? TextureFilter::kNearest
                                                                        : TextureFilter::kLinear;
    }
    return textureIds_[info.index] = out_.scene.AddTexture(texture, rgba.data());
}

}  // namespace rtrt
