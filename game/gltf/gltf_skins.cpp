#include "game/gltf/gltf_skins.h"

#include <algorithm>
#include <string>

#include "game/gltf/gltf_accessors.h"
#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

std::vector<glm::mat4> InverseBindMatrices(const GltfDocument& doc, const tinygltf::Skin& skin,
                                           const std::string& at) {
    const size_t joints = skin.joints.size();
    if (skin.inverseBindMatrices < 0) return std::vector<glm::mat4>(joints, glm::mat4(1.0f));
    const std::string field = at + ".inverseBindMatrices";
    const AccessorView a = GltfAccessor(doc, skin.inverseBindMatrices, field, {TINYGLTF_TYPE_MAT4});
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        doc.Fail(field, "inverse bind matrices must be floats");
    if (a.count < joints)
        doc.Fail(field,
                 std::to_string(a.count) + " matrices for " + std::to_string(joints) + " joints");
    std::vector<glm::mat4> matrices(joints);
    for (size_t j = 0; j < joints; ++j)
        for (int c = 0; c < 16; ++c) {
            const float v = a.Component(j, c);
            if (!FiniteFloat(v))
                doc.Fail(field, "matrix " + std::to_string(j) + ": NaN or infinite");
            matrices[j][c / 4][c % 4] = v;  // glTF matrices are column-major, as glm's
        }
    return matrices;
}

}  // namespace

void CheckGltfSkinJoints(const GltfDocument& doc) {
    const tinygltf::Model& model = doc.Model();
    for (size_t i = 0; i < model.skins.size(); ++i) {
        const tinygltf::Skin& skin = model.skins[i];
        const std::string at = JsonIndexed("skins", i) + ".joints";
        if (skin.joints.empty()) doc.Fail(at, "a skin needs at least one joint");
        // glTF's joints are unique: a node listed twice is two joints that cannot differ.
        std::vector<int> sorted = skin.joints;
        std::sort(sorted.begin(), sorted.end());
        if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
            twice != sorted.end())
            doc.Fail(at, "node " + std::to_string(*twice) + " is listed twice");
    }
}

void ReadGltfSkins(GltfDocument& doc, const std::vector<int32_t>& nodeSlot, GltfAsset& asset) {
    const tinygltf::Model& model = doc.Model();
    asset.skins.resize(model.skins.size());
    // The skins the scene shown uses: another scene's may have its joints there.
    std::vector<bool> used(model.skins.size(), false);
    for (size_t n = 0; n < model.nodes.size(); ++n) {
        const int skin = model.nodes[n].skin;
        if (nodeSlot[n] >= 0 && skin >= 0 && size_t(skin) < used.size()) used[size_t(skin)] = true;
    }
    for (size_t i = 0; i < model.skins.size(); ++i) {
        const tinygltf::Skin& skin = model.skins[i];
        const std::string at = JsonIndexed("skins", i);
        auto slotOf = [&](int node, const std::string& field) {
            if (node < 0 || size_t(node) >= model.nodes.size())
                doc.Fail(field, "node " + std::to_string(node) + " out of range");
            if (nodeSlot[size_t(node)] < 0 && used[i])
                doc.Fail(field, "node " + std::to_string(node) + " is not in the scene shown");
            return nodeSlot[size_t(node)];
        };
        GltfSkin& out = asset.skins[i];
        if (skin.skeleton >= 0) out.skeleton = slotOf(skin.skeleton, at + ".skeleton");
        if (!used[i]) {  // its fields checked, nothing of it is shown
            for (size_t j = 0; j < skin.joints.size(); ++j)
                slotOf(skin.joints[j], JsonIndexed(at + ".joints", j));
            continue;
        }
        try {
            out.inverseBind = InverseBindMatrices(doc, skin, at);
        } catch (const GltfUnsupported& u) {
            doc.Warn("unsupported:" + u.what, at + ".inverseBindMatrices: " + u.what +
                                                  "; what it skins keeps its rest pose");
            continue;
        }
        for (size_t j = 0; j < skin.joints.size(); ++j)
            out.joints.push_back(slotOf(skin.joints[j], JsonIndexed(at + ".joints", j)));
    }
}

}  // namespace rtrt
