#include "game/gltf/gltf_textures.h"

#include "engine/render_rt/shading/texture_mips.h"
#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

TextureWrap Wrap(int mode) {
    if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::kClampToEdge;
    if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::kMirroredRepeat;
    return TextureWrap::kRepeat;
}

}  // namespace

uint32_t GltfTextures::Slot(const GltfTextureRef& ref, const std::string& at, bool srgb,
                            TexelChannels channels) {
    if (ref.index < 0) return kNoTexture;
    if (size_t(ref.index) >= model_.textures.size())
        doc_.Fail(at + ".index", "texture " + std::to_string(ref.index) + " out of range");
    Texture texture;
    if (!ReadTransform(ref, at, &texture)) return kNoTexture;
    const Texture* decoded = Decoded(ref.index, srgb, channels, at);
    if (!decoded) return kNoTexture;
    const std::vector<float> transform(texture.uvTransform, texture.uvTransform + 6);
    const auto key = std::make_tuple(ref.index, srgb, channels,
                                     texture.transformed ? transform : std::vector<float>{});
    auto found = records_.find(key);
    if (found != records_.end()) return found->second;
    Texture record = *decoded;
    record.srgb = srgb ? 1 : 0;
    record.transformed = texture.transformed;
    for (int i = 0; i < 6; ++i) record.uvTransform[i] = texture.uvTransform[i];
    return records_[key] = out_.scene.AddTextureView(record);
}

// KHR_texture_transform's offset, rotation and scale; its texCoord override counts as the
// slot's. False (with a warning) where the slot reads another coordinate set than TEXCOORD_0.
bool GltfTextures::ReadTransform(const GltfTextureRef& ref, const std::string& at,
                                 Texture* texture) {
    int texCoord = ref.texCoord;
    const tinygltf::Value* transform = nullptr;
    if (ref.extensions) {
        auto it = ref.extensions->find("KHR_texture_transform");
        if (it != ref.extensions->end()) transform = &it->second;
    }
    if (transform) {
        const std::string tat = at + ".extensions.KHR_texture_transform";
        if (!transform->IsObject()) doc_.Fail(tat, "expected an object");
        auto number = [&](const tinygltf::Value& v, const std::string& field) {
            if (!v.IsNumber() || !FiniteFloat(v.GetNumberAsDouble()) ||
                std::fabs(v.GetNumberAsDouble()) > 1e6)
                doc_.Fail(tat + "." + field, "expected a number between -1e6 and 1e6");
            return float(v.GetNumberAsDouble());
        };
        auto pair = [&](const char* field, vec2 fallback) {
            if (!transform->Has(field)) return fallback;
            const tinygltf::Value& v = transform->Get(field);
            if (!v.IsArray() || v.ArrayLen() != 2)
                doc_.Fail(tat + "." + field, "expected 2 numbers");
            return vec2(number(v.Get(0), field), number(v.Get(1), field));
        };
        const vec2 offset = pair("offset", vec2(0.0f));
        const vec2 scale = pair("scale", vec2(1.0f));
        const float rotation =
            transform->Has("rotation") ? number(transform->Get("rotation"), "rotation") : 0.0f;
        if (transform->Has("texCoord")) {
            const tinygltf::Value& v = transform->Get("texCoord");
            if (!v.IsInt() || v.GetNumberAsInt() < 0)
                doc_.Fail(tat + ".texCoord", "expected a non-negative integer");
            texCoord = v.GetNumberAsInt();
        }
        SetUvTransform(texture, offset, rotation, scale);
    }
    if (texCoord != 0) {
        doc_.Warn("texcoord", at + ".texCoord: only TEXCOORD_0 is supported; the slot is unused");
        return false;
    }
    return true;
}

const Texture* GltfTextures::Decoded(int index, bool srgb, TexelChannels wanted,
                                     const std::string& at) {
    const auto key = std::make_tuple(index, srgb, wanted);
    auto found = decoded_.find(key);
    if (found != decoded_.end()) return found->second.width == 0 ? nullptr : &found->second;
    const tinygltf::Texture& t = model_.textures[size_t(index)];
    const std::string textureAt = JsonIndexed("textures", size_t(index));
    if (t.source < 0) {
        doc_.Warn("texture-source", textureAt +
                                        ": no image rtrt can read (an extension's "
                                        "format?); the slot at " +
                                        at + " is unused");
        decoded_[key] = Texture{0, 0, 0};
        return nullptr;
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
    Texture texture;
    texture.width = uint32_t(image.width);
    texture.height = uint32_t(image.height);
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
    // Minification without mip levels only where the sampler asks for it (NEAREST or LINEAR);
    // glTF leaves the filter to the renderer when it names none.
    bool mipmapped = true;
    if (t.sampler >= 0) {
        const int minFilter = model_.samplers[size_t(t.sampler)].minFilter;
        mipmapped = minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
                    minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR;
    }
    texture.levels = mipmapped ? FullMipLevels(texture.width, texture.height) : 1;
    // The texels go in once per image, encoding and mip chain, however many textures name the
    // image (64 textures of one 4096^2 image had built 64 chains); each slot's record (Slot)
    // points at them.
    const auto texelsKey = std::make_tuple(t.source, srgb, texture.levels, wanted);
    if (auto shared = texels_.find(texelsKey); shared != texels_.end()) {
        texture.texelOffset = shared->second;
        return &(decoded_[key] = texture);
    }
    std::vector<uint32_t> rgba(size_t(image.width) * size_t(image.height));
    for (size_t p = 0; p < rgba.size(); ++p) {
        uint32_t c[4] = {0, 0, 0, 255};
        for (int k = 0; k < channels; ++k) {
            // 16-bit images keep their high byte, little-endian as stb and OIIO return them.
            c[k] =
                image.image[(p * size_t(channels) + size_t(k)) * size_t(bytes) + size_t(bytes - 1)];
        }
        if (channels == 2) c[3] = c[1];         // grey and alpha
        if (channels <= 2) c[1] = c[2] = c[0];  // grey
        if (wanted == TexelChannels::kAlphaAsGrey) c[0] = c[1] = c[2] = c[3];
        rgba[p] = c[0] | (c[1] << 8) | (c[2] << 16) | (c[3] << 24);
    }
    const std::vector<uint32_t> chain =
        BuildMipChain(rgba.data(), texture.width, texture.height, texture.levels, srgb);
    texture.texelOffset = out_.scene.AddTexels(chain.data(), chain.size());
    texels_[texelsKey] = texture.texelOffset;
    return &(decoded_[key] = texture);
}

}  // namespace rtrt
