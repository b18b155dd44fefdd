#include "game/gltf/gltf_materials.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "game/scene/json_fields.h"

namespace rtrt {

namespace fs = std::filesystem;

namespace {

// A bound or a value as a message shows it: 1, not 1.000000.
std::string Shortest(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

}  // namespace

// Larger indices are kept at this one: its reflectance differs from 1 by under 4e-6, and the
// refraction's eta^2 stays finite in float.
constexpr float kLargestIor = 1e6f;

// glTF's metallic-roughness material as the PBR material it is, with rtrt's Blinn-Phong version of
// it (the README's table says how) for kernels without PBR.
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
            doc_.Fail(at + "." + name, "must be between " + Shortest(lo) + " and " + Shortest(hi) +
                                           ", got " + Shortest(v));
        return float(v);
    };
    // glTF bounds both factors' components to [0, 1] (KHR_materials_emissive_strength makes
    // emission brighter); a base colour's alpha too, though surfaces are opaque. Exporters have
    // written larger ones (three.js before r129 put emissive x intensity there), which other
    // viewers load: those are clamped, with a warning.
    auto component = [&](double v, const std::string& name) {
        const float c = number(v, name, 0, 1e6);
        if (c > 1.0f)
            doc_.Warn("factor-above-1:" + name, at + "." + name +
                                                    ": components above 1 (glTF's bound) are "
                                                    "taken as 1, e.g. " +
                                                    Shortest(v));
        return std::min(c, 1.0f);
    };
    auto colour = [&](const std::vector<double>& v, const std::string& name, vec3 fallback) {
        if (v.empty()) return fallback;
        if (v.size() < 3) doc_.Fail(at + "." + name, "expected 3 or 4 numbers");
        if (v.size() > 3) component(v[3], name);
        return vec3(component(v[0], name), component(v[1], name), component(v[2], name));
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
    // KHR_materials_ior: at least 1, or 0, the specular-glossiness compatibility mode: an infinite
    // index, whose Fresnel term is 1 at every angle, so that nothing is transmitted.
    const double iorValue = extension("KHR_materials_ior", "ior", 1.5);
    if (!(iorValue == 0.0 || (iorValue >= 1.0 && std::isfinite(iorValue))))
        doc_.Fail(at + ".extensions.KHR_materials_ior.ior", "must be 0 or at least 1");
    const bool infiniteIor = iorValue == 0.0;
    const float ior = infiniteIor ? kLargestIor : float(std::min(iorValue, double(kLargestIor)));
    const float transmissionFactor =
        number(extension("KHR_materials_transmission", "transmissionFactor", 0.0),
               "extensions.KHR_materials_transmission.transmissionFactor", 0, 1);
    const float transmission = infiniteIor ? 0.0f : transmissionFactor;
    // KHR_materials_transmission alone describes a thin wall (a window pane, a leaf): refraction
    // needs KHR_materials_volume with a thickness above 0 (its default is 0, thin).
    const float thickness = number(extension("KHR_materials_volume", "thicknessFactor", 0.0),
                                   "extensions.KHR_materials_volume.thicknessFactor", 0, 1e30);
    const bool thinWalled = thickness == 0.0f;
    if (!thinWalled && g.extensions.count("KHR_materials_volume") &&
        (g.extensions.at("KHR_materials_volume").Has("attenuationColor") ||
         g.extensions.at("KHR_materials_volume").Has("attenuationDistance")))
        doc_.Warn("volume-attenuation", at + ".extensions.KHR_materials_volume: attenuation "
                                             "inside the volume is not applied");
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
            name != "KHR_materials_specular" && name != "KHR_materials_emissive_strength" &&
            name != "KHR_materials_volume")
            doc_.Warn("material:" + name,
                      at + ".extensions." + name + ": not supported; the material ignores it");
    if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty())
        doc_.Warn("alpha",
                  at + ".alphaMode: " + g.alphaMode + " is not supported; surfaces are opaque");

    // Dielectric reflectance at normal incidence from the index of refraction, scaled by
    // KHR_materials_specular; metals reflect their base colour (the glTF BRDF's F0).
    const float f0Dielectric =
        infiniteIor ? 1.0f : ((ior - 1.0f) / (ior + 1.0f)) * ((ior - 1.0f) / (ior + 1.0f));
    const vec3 f0 = glm::mix(
        glm::min(vec3(f0Dielectric) * specularColour, vec3(1.0f)) * specularFactor, base, metallic);
    const float smooth = (1.0f - roughness) * (1.0f - roughness);
    Material m;
    m.diffuse = base * (1.0f - metallic) * (1.0f - transmission);
    m.specular = f0;
    // Blinn-Phong exponent of the same highlight width as GGX of alpha = roughness^2
    // (Walter et al. 2007): n = 2 / alpha^2 - 2.
    const float alpha = std::max(roughness * roughness, 0.01f);
    m.shininess = std::clamp(2.0f / (alpha * alpha) - 2.0f, 1.0f, 10000.0f);
    m.transmissivity = transmission * (1.0f - metallic);
    m.reflectivity =
        std::min(std::max(std::max(f0.x, f0.y), f0.z) * smooth, 1.0f - m.transmissivity);
    m.ior = ior;
    m.thinWalled = thinWalled ? 1u : 0u;
    m.baseColorTexture = textures_.Slot({pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                         &pbr.baseColorTexture.extensions},
                                        at + ".pbrMetallicRoughness.baseColorTexture", true);

    PbrMaterial p;
    p.baseColor = base;
    p.metallic = metallic;
    p.roughness = roughness;
    p.emissive = emissive;
    p.dielectricF0 = vec3(f0Dielectric) * specularColour;  // kept at most 1 where shaded
    p.specularWeight = specularFactor;
    p.transmission = transmission;
    p.ior = ior;
    p.thinWalled = thinWalled ? 1u : 0u;
    p.normalScale = number(g.normalTexture.scale, "normalTexture.scale", -1e3, 1e3);
    p.occlusionStrength = number(g.occlusionTexture.strength, "occlusionTexture.strength", 0, 1);
    p.metallicRoughnessTexture =
        textures_.Slot({pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                        &pbr.metallicRoughnessTexture.extensions},
                       at + ".pbrMetallicRoughness.metallicRoughnessTexture", false);
    p.normalTexture = textures_.Slot(
        {g.normalTexture.index, g.normalTexture.texCoord, &g.normalTexture.extensions},
        at + ".normalTexture", false);
    p.occlusionTexture = textures_.Slot(
        {g.occlusionTexture.index, g.occlusionTexture.texCoord, &g.occlusionTexture.extensions},
        at + ".occlusionTexture", false);
    p.emissiveTexture = textures_.Slot(
        {g.emissiveTexture.index, g.emissiveTexture.texCoord, &g.emissiveTexture.extensions},
        at + ".emissiveTexture", true);
    p.transmissionTexture =
        ExtensionSlot(g, at, "KHR_materials_transmission", "transmissionTexture", false);
    p.specularTexture = ExtensionSlot(g, at, "KHR_materials_specular", "specularTexture", false,
                                      TexelChannels::kAlphaAsGrey);
    p.specularColorTexture =
        ExtensionSlot(g, at, "KHR_materials_specular", "specularColorTexture", true);
    m.ambient = GltfApproximationAmbient(p);
    const uint32_t id = out_.scene.AddPbrMaterial(m, p);
    out_.materialNames.push_back(
        g.name.empty() ? fs::path(doc_.File()).filename().string() + " " + at : g.name);
    materialIds_[index] = id;
    return id;
}

// A textureInfo inside a material extension's object, which tinygltf keeps as a JSON value (its
// fields' kinds and index were checked before the file was read).
uint32_t GltfMaterials::ExtensionSlot(const tinygltf::Material& g, const std::string& at,
                                      const char* extension, const char* key, bool srgb,
                                      TexelChannels channels) {
    auto it = g.extensions.find(extension);
    if (it == g.extensions.end() || !it->second.Has(key)) return kNoTexture;
    const tinygltf::Value& info = it->second.Get(key);
    const std::string field = at + ".extensions." + extension + "." + key;
    if (!info.Has("index")) doc_.Fail(field + ".index", "missing (glTF 2.0 requires it)");
    tinygltf::ExtensionMap extensions;
    if (info.Has("extensions")) extensions = info.Get("extensions").Get<tinygltf::Value::Object>();
    const int texCoord = info.Has("texCoord") ? info.Get("texCoord").GetNumberAsInt() : 0;
    return textures_.Slot({info.Get("index").GetNumberAsInt(), texCoord, &extensions}, field, srgb,
                          channels);
}

}  // namespace rtrt
