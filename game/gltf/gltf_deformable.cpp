#include "game/gltf/gltf_deformable.h"

#include <algorithm>
#include <vector>

#include "game/gltf/gltf_accessors.h"
#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

// Targets can share one accessor, so the deltas a file asks for are not bounded by its size:
// beyond this many (768 MiB of positions) a file is refused rather than exhausting memory.
constexpr uint64_t kMaxMorphDeltas = uint64_t(1) << 26;

int Attribute(const tinygltf::Primitive& prim, const std::string& name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
}

// One JOINTS_n / WEIGHTS_n pair, checked against the spec's component types and the vertex count.
struct InfluenceSet {
    AccessorView joints, weights;
    std::string jointsAt, weightsAt;
};

InfluenceSet ReadInfluenceSet(const GltfDocument& doc, const tinygltf::Primitive& prim,
                              const std::string& at, int set, size_t vertices) {
    const std::string j = "JOINTS_" + std::to_string(set), w = "WEIGHTS_" + std::to_string(set);
    InfluenceSet s;
    s.jointsAt = at + ".attributes." + j;
    s.weightsAt = at + ".attributes." + w;
    const int jointsIndex = Attribute(prim, j), weightsIndex = Attribute(prim, w);
    if (jointsIndex < 0) doc.Fail(s.weightsAt, "given without " + j);
    if (weightsIndex < 0) doc.Fail(s.jointsAt, "given without " + w);
    s.joints = GltfAccessor(doc, jointsIndex, s.jointsAt, {TINYGLTF_TYPE_VEC4});
    if ((s.joints.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         s.joints.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) ||
        s.joints.normalized)
        doc.Fail(s.jointsAt,
                 "joint indices must be unsigned bytes or unsigned shorts (not "
                 "normalised)");
    s.weights = GltfAccessor(doc, weightsIndex, s.weightsAt, {TINYGLTF_TYPE_VEC4});
    const bool normalisedInteger =
        s.weights.normalized && (s.weights.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                 s.weights.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    if (s.weights.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !normalisedInteger)
        doc.Fail(s.weightsAt, "weights must be floats or normalised unsigned bytes or shorts");
    auto sameCount = [&](const AccessorView& a, const std::string& field) {
        if (a.count != vertices)
            doc.Fail(field, std::to_string(a.count) + " elements, but POSITION has " +
                                std::to_string(vertices));
    };
    sameCount(s.joints, s.jointsAt);
    sameCount(s.weights, s.weightsAt);
    return s;
}

}  // namespace

bool ReadGltfSkinInfluences(GltfDocument& doc, const tinygltf::Primitive& prim,
                            const std::string& at, uint32_t jointCount, DeformableMesh& out,
                            bool& nodeJoint) {
    const size_t vertices = out.rest.positions.size();
    std::vector<InfluenceSet> sets;
    try {
        for (int set = 0; set < 2; ++set) {
            if (Attribute(prim, "JOINTS_" + std::to_string(set)) < 0 &&
                Attribute(prim, "WEIGHTS_" + std::to_string(set)) < 0)
                break;
            sets.push_back(ReadInfluenceSet(doc, prim, at, set, vertices));
        }
    } catch (const GltfUnsupported& u) {
        doc.Warn("unsupported:" + u.what,
                 at + ": " + u.what + "; the primitive is drawn unskinned");
        return false;
    }
    if (sets.empty()) {
        doc.Warn("skin-without-joints", at + ".attributes: its node has a skin but the "
                                             "primitive has no JOINTS_0; it is drawn unskinned");
        return false;
    }
    if (Attribute(prim, "JOINTS_2") >= 0)
        doc.Warn("influences", at + ".attributes.JOINTS_2: rtrt follows at most 8 joints per "
                                    "vertex; sets after JOINTS_1/WEIGHTS_1 are ignored");
    const uint32_t n = uint32_t(4 * sets.size());
    out.influences = n;
    out.joints.assign(vertices * n, 0);
    out.weights.assign(vertices * n, 0.0f);
    nodeJoint = false;
    for (size_t v = 0; v < vertices; ++v) {
        float sum = 0.0f;
        for (size_t s = 0; s < sets.size(); ++s)
            for (int c = 0; c < 4; ++c) {
                const float w = sets[s].weights.Component(v, c);
                if (!FiniteFloat(w) || w < 0.0f)
                    doc.Fail(sets[s].weightsAt, "vertex " + std::to_string(v) +
                                                    ": a weight is negative or not finite");
                const uint32_t joint = uint32_t(sets[s].joints.Component(v, c));
                if (w > 0.0f && joint >= jointCount)
                    doc.Fail(sets[s].jointsAt, "vertex " + std::to_string(v) + ": joint " +
                                                   std::to_string(joint) +
                                                   " out of range (the skin has " +
                                                   std::to_string(jointCount) + " joints)");
                const size_t slot = v * n + 4 * s + size_t(c);
                out.joints[slot] = w > 0.0f ? joint : 0;  // an unused slot's index is arbitrary
                out.weights[slot] = w;
                sum += w;
            }
        if (sum > 0.0f) {
            for (uint32_t i = 0; i < n; ++i) out.weights[v * n + i] /= sum;
        } else {
            out.joints[v * n] = jointCount;  // the mesh's own node: it stays in its rest place
            out.weights[v * n] = 1.0f;
            nodeJoint = true;
        }
    }
    out.jointCount = jointCount + (nodeJoint ? 1 : 0);
    return true;
}

bool ReadGltfMorphTargets(GltfDocument& doc, const tinygltf::Primitive& prim, const std::string& at,
                          const tinygltf::Mesh& mesh, const std::string& meshAt,
                          DeformableMesh& out, uint64_t& fileDeltas) {
    if (prim.targets.empty()) {
        // The mesh's weights are one per morph target of each primitive: none without targets.
        if (!mesh.weights.empty())
            doc.Fail(meshAt + ".weights", std::to_string(mesh.weights.size()) +
                                              " weights for 0 morph targets (" + at +
                                              " has no targets)");
        return false;
    }
    const size_t vertices = out.rest.positions.size(), targets = prim.targets.size();
    const bool hasNormals = !out.rest.normals.empty();
    // Targets of many primitives can share one accessor too: the budget is the file's.
    if (uint64_t(targets) * vertices > kMaxMorphDeltas - std::min(fileDeltas, kMaxMorphDeltas))
        doc.Fail(at + ".targets", std::to_string(targets) + " targets of " +
                                      std::to_string(vertices) +
                                      " vertices take the file's morph deltas past what rtrt "
                                      "holds (" +
                                      std::to_string(kMaxMorphDeltas) + " in all)");
    fileDeltas += uint64_t(targets) * vertices;
    std::vector<vec3> positions(targets * vertices, vec3(0.0f)), normals;
    try {
        for (size_t t = 0; t < targets; ++t) {
            const std::string targetAt = JsonIndexed(at + ".targets", t);
            for (const auto& [name, accessor] : prim.targets[t]) {
                if (name == "TANGENT") continue;  // rtrt reads no tangents at all
                if (name != "POSITION" && name != "NORMAL") {
                    doc.Warn("morph:" + name,
                             targetAt + "." + name + ": morph deltas of " + name +
                                 " are ignored (rtrt morphs positions and normals)");
                    continue;
                }
                if (name == "NORMAL" && !hasNormals) continue;  // flat shading: nothing to move
                const std::vector<vec3> deltas =
                    ReadGltfFloats<3>(doc, accessor, targetAt + "." + name, TINYGLTF_TYPE_VEC3);
                if (deltas.size() != vertices)
                    doc.Fail(targetAt + "." + name, std::to_string(deltas.size()) +
                                                        " deltas, but POSITION has " +
                                                        std::to_string(vertices) + " vertices");
                std::vector<vec3>& block = name == "POSITION" ? positions : normals;
                if (block.empty()) block.assign(targets * vertices, vec3(0.0f));
                std::copy(deltas.begin(), deltas.end(),
                          block.begin() + std::ptrdiff_t(t * vertices));
            }
        }
    } catch (const GltfUnsupported& u) {
        doc.Warn("unsupported:" + u.what,
                 at + ".targets: " + u.what + "; the primitive keeps its base shape");
        return false;
    }
    if (!mesh.weights.empty() && mesh.weights.size() != targets)
        doc.Fail(meshAt + ".weights", std::to_string(mesh.weights.size()) + " weights for " +
                                          std::to_string(targets) + " morph targets");
    out.defaultWeights.assign(targets, 0.0f);
    for (size_t t = 0; t < mesh.weights.size(); ++t) {
        if (!FiniteFloat(mesh.weights[t]))
            doc.Fail(meshAt + ".weights", "a weight is NaN or infinite (or beyond float range)");
        out.defaultWeights[t] = float(mesh.weights[t]);
    }
    out.targetCount = uint32_t(targets);
    out.positionDeltas = std::move(positions);
    out.normalDeltas = std::move(normals);
    return true;
}

}  // namespace rtrt
