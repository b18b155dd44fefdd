#include "game/gltf/gltf_import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>

#include "engine/core/error.h"
#include "game/gltf/gltf_accessors.h"
#include "game/gltf/gltf_animation.h"
#include "game/gltf/gltf_document.h"
#include "game/gltf/gltf_materials.h"
#include "game/gltf/gltf_meshes.h"
#include "game/gltf/gltf_nodes.h"
#include "game/gltf/gltf_skins.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

void CheckExtensions(GltfDocument& doc) {
    static const std::set<std::string> kUsed = {
        "KHR_lights_punctual",        "KHR_materials_transmission",      "KHR_materials_ior",
        "KHR_materials_specular",     "KHR_materials_emissive_strength", "KHR_texture_transform",
        "KHR_draco_mesh_compression", "KHR_mesh_quantization",           "KHR_materials_volume"};
    for (const std::string& ext : doc.Model().extensionsRequired)
        if (!kUsed.count(ext))
            doc.Warn("ext:" + ext, "extensionsRequired: " + ext +
                                       " is not supported; what needs it is ignored or skipped");
}

// The world bounds of what the scene shows at its start.
Aabb SceneBounds(const LoadedScene& out) {
    const std::vector<glm::mat4> worlds = InitialWorlds(out);
    Aabb bounds;
    for (size_t i = 0; i < out.entities.size(); ++i) {
        const EntityDesc& e = out.entities[i];
        if (!e.renderable) continue;
        const Aabb b = out.scene.blases[e.blasId]->bounds;
        auto grow = [&](const glm::mat4& toWorld) {
            for (int corner = 0; corner < 8; ++corner) {
                const vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                             (corner & 4) ? b.max.z : b.min.z);
                bounds.Grow(vec3(toWorld * glm::vec4(p, 1.0f)));
            }
        };
        if (!e.skin) {
            grow(worlds[i]);
            continue;
        }
        // A skinned vertex is a weighted mean of its joints' transforms of it, all inside the
        // boxes each joint makes of the mesh's; the skinned node's own transform does not apply
        // (glTF 2.0, 3.7.3.3): framed by it, the camera had looked elsewhere.
        for (size_t k = 0; k < e.skin->joints.size(); ++k)
            grow(worlds[size_t(e.skin->joints[k])] * e.skin->inverseBind[k]);
    }
    return bounds;
}

// A camera that sees the whole scene from the front (+z), a little above and to the right, so
// that a box shows three faces.
Camera FramingCamera(const LoadedScene& out) {
    const Aabb bounds = SceneBounds(out);
    Camera camera;
    const vec3 centre = 0.5f * (bounds.min + bounds.max);
    const float radius = std::max(0.5f * glm::length(bounds.Extent()), 1e-3f);
    const float distance = radius / std::tan(glm::radians(0.5f * camera.fovYDegrees));
    const vec3 from = glm::normalize(vec3(0.6f, 0.5f, 1.0f));
    camera.position = centre + from * (distance * 1.1f);
    camera.forward = -from;
    return camera;
}

// The key light's level: the largest colour component any light gives a white surface facing it
// at the centre of the scene, directional lights everywhere, point and spot lights at their
// distance (at least a quarter of the scene's radius, so that a lamp inside the scene does not
// set it), their cones and ranges aside: where they shine. 0 without lights.
float KeyLight(const LoadedScene& out) {
    const Aabb bounds = SceneBounds(out);
    const vec3 centre = bounds.Centroid();
    const float nearest = 0.125f * glm::length(bounds.Extent());
    float key = 0.0f;
    for (const Light& light : out.scene.lights) {
        float level = MaxComponent(light.color);
        if (light.type != LightType::kDirectional && light.falloff != 0) {
            const float d = std::max(glm::length(light.vector - centre), nearest);
            level /= std::max(d * d, 1e-12f);
        }
        key = std::max(key, level);
    }
    return key;
}

// A glTF file's lights are in physical units, lux and candela, which may be tens of thousands:
// its exposure makes a white surface facing the key light show 1 before tone mapping (within the
// scene files' exposure range), and the ambient light that stands for indirect light (a tenth of
// the key) and the sky scale with it, in the PBR materials and their Blinn-Phong approximations.
void ExposeForKeyLight(LoadedScene& out) {
    const float key = KeyLight(out);
    if (!(key > 0.0f) || !std::isfinite(key)) return;
    out.output.exposureEv = std::clamp(-std::log2(key), -20.0f, 20.0f);
    for (Material& m : out.scene.materials) {
        if (m.pbrMaterial == kNoPbrMaterial) continue;
        PbrMaterial& p = out.scene.pbrMaterials[m.pbrMaterial];
        p.ambientLight = vec3(0.1f * key);
        m.ambient = GltfApproximationAmbient(p);
    }
    out.scene.background *= key;
}

GltfAsset ReadGltfAsset(const std::string& path, LoadedScene& out) {
    GltfDocument doc(path);
    CheckExtensions(doc);
    const tinygltf::Model& model = doc.Model();
    GltfAsset asset;
    asset.summary.file = path;
    asset.summary.meshes = uint32_t(model.meshes.size());
    asset.summary.textures = uint32_t(model.textures.size());
    asset.summary.materials = uint32_t(model.materials.size());
    asset.summary.animations = uint32_t(model.animations.size());
    const std::vector<int> parentOf = CheckGltfNodeGraph(doc);
    CheckGltfSkinJoints(doc);
    ReadGltfCamerasAndLights(doc, asset);
    GltfMaterials materials(doc, out);
    GltfMeshes meshes(doc, out, materials, asset.summary);
    const std::vector<int32_t> nodeSlot = ReadGltfNodes(doc, parentOf, meshes, asset);
    ReadGltfSkins(doc, nodeSlot, asset);
    ReadGltfAnimation(doc, nodeSlot, asset);
    asset.summary.skins = uint32_t(model.skins.size());
    return asset;
}

}  // namespace

bool IsGltfPath(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".gltf" || ext == ".glb";
}

GltfAsset LoadGltfAsset(const std::string& path, LoadedScene& out) {
    // Content rtrt skips is caught where it can be skipped; anywhere else it is bad input.
    try {
        return ReadGltfAsset(path, out);
    } catch (const GltfUnsupported& u) {
        throw InputError(path, "", u.what);
    }
}

LoadedScene LoadGltfScene(const std::string& path) {
    LoadedScene out;
    out.output = kLinearToSrgb;  // glTF's colours are linear light (its specification)
    const GltfAsset asset = LoadGltfAsset(path, out);
    out.gltfFiles.push_back(asset.summary);
    if (const uint64_t entities = GltfEntityCount(asset); entities > kMaxSceneEntities)
        throw InputError(path, "nodes",
                         "the scene's nodes and primitives make " + std::to_string(entities) +
                             " entities; a scene may have at most 2,000,000");
    const std::optional<Camera> camera = InstantiateGltf(asset, out, -1, glm::mat4(1.0f));
    bool anything = false;
    for (const EntityDesc& e : out.entities) anything |= e.renderable;
    if (!anything) throw InputError(path, "meshes", "the scene has no triangles to render");
    if (camera) {
        out.scene.camera = *camera;
        for (const GltfNode& n : asset.nodes)
            if (n.camera >= 0) {
                const float aspect = asset.cameras[size_t(n.camera)].aspect;
                if (aspect > 0.0f) {
                    out.width = 1280;
                    // Clamped before rounding: 1280 / 1e-30 is beyond what lround returns.
                    out.height = uint32_t(std::lround(std::clamp(1280.0 / aspect, 1.0, 16384.0)));
                }
                break;
            }
    } else {
        out.scene.camera = FramingCamera(out);
    }
    if (out.scene.lights.empty()) {
        Light light;
        light.vector = glm::normalize(vec3(1.0f, 1.0f, 1.0f));
        out.scene.lights.push_back(light);
    }
    ExposeForKeyLight(out);
    FinishLoadedScene(out, path);
    return out;
}

}  // namespace rtrt
