#include "game/gltf/gltf_meshes.h"

#include <algorithm>
#include <filesystem>
#include <memory>

#include "engine/bvh/blas/blas.h"
#include "engine/geometry/mesh_tangents.h"
#include "game/gltf/gltf_accessors.h"
#include "game/gltf/gltf_deformable.h"
#include "game/scene/json_fields.h"

namespace rtrt {

namespace fs = std::filesystem;

std::vector<GltfPrimitive> GltfMeshes::Primitives(size_t mesh, int skin) {
    auto found = meshPrimitives_.find({mesh, skin});
    if (found != meshPrimitives_.end()) return found->second;
    std::vector<GltfPrimitive> result;
    const tinygltf::Mesh& m = model_.meshes[mesh];
    for (size_t p = 0; p < m.primitives.size(); ++p) {
        const tinygltf::Primitive& prim = m.primitives[p];
        const std::string at = JsonIndexed(JsonIndexed("meshes", mesh) + ".primitives", p);
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            prim.mode != TINYGLTF_MODE_TRIANGLE_FAN && prim.mode != -1) {
            doc_.Warn("mode", at + ".mode: mode " + std::to_string(prim.mode) +
                                  " (points or lines) has no surface to trace; such primitives "
                                  "are skipped");
            continue;
        }
        if (prim.targets.size() != m.primitives[0].targets.size())
            doc_.Fail(at + ".targets", std::to_string(prim.targets.size()) +
                                           " morph targets, but primitive 0 has " +
                                           std::to_string(m.primitives[0].targets.size()));
        // A primitive that does not deform is its accessors, its mode and whether its material
        // wants tangents: one that names what an earlier one named shares its BLAS. Under a
        // skin it is read whole, so that its skin attributes are checked wherever it is shown.
        const bool shared = prim.targets.empty() && skin < 0;
        std::string key;
        if (shared) {
            key = std::to_string(prim.indices) + "/" + std::to_string(prim.mode) + "/" +
                  (NormalMapped(prim) ? "t" : "");
            for (const auto& [name, accessor] : prim.attributes)
                key += "/" + name + "=" + std::to_string(accessor);
            if (auto shared = staticGeometry_.find(key); shared != staticGeometry_.end()) {
                summary_.primitives++;
                summary_.vertices += shared->second.vertices;
                summary_.triangles += shared->second.triangles;
                GltfPrimitive out;
                out.blas = shared->second.blas;
                out.material = materials_.Id(prim.material, at + ".material");
                result.push_back(out);
                continue;
            }
        }
        TriangleMesh triangles;
        try {
            triangles = ReadPrimitive(prim, at);
        } catch (const GltfUnsupported& u) {
            doc_.Warn("unsupported:" + u.what, at + ": " + u.what + "; the primitive is skipped");
            continue;
        }
        if (triangles.indices.empty()) continue;
        AddTangents(prim, at, skin, triangles);
        summary_.primitives++;
        summary_.vertices += uint32_t(triangles.positions.size());
        summary_.triangles += uint32_t(triangles.indices.size());
        GltfPrimitive out;
        // The BLAS's primIds index triangles.indices: a deformable mesh's rest pose is these very
        // triangles, so that the frame renderer can deform them in the tree's order.
        out.blas = out_.scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(triangles)));
        out_.modelNames.push_back(fs::path(doc_.File()).filename().string() + " " + at +
                                  (m.name.empty() ? "" : " (" + m.name + ")"));
        out.material = materials_.Id(prim.material, at + ".material");
        if (triangles.uvs.empty() && Textured(prim))
            doc_.Warn("no-texcoord", at + ": its material has textures, but the primitive has "
                                          "no TEXCOORD_0 (glTF requires it); they are not applied");
        ReadDeformation(prim, at, mesh, skin, triangles, out);
        if (shared)
            staticGeometry_[key] = {out.blas, uint32_t(triangles.positions.size()),
                                    uint32_t(triangles.indices.size())};
        result.push_back(out);
    }
    meshPrimitives_[{mesh, skin}] = result;
    return result;
}

bool GltfMeshes::Textured(const tinygltf::Primitive& prim) const {
    if (prim.material < 0 || size_t(prim.material) >= model_.materials.size()) return false;
    const tinygltf::Material& m = model_.materials[size_t(prim.material)];
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    if (pbr.baseColorTexture.index >= 0 || pbr.metallicRoughnessTexture.index >= 0 ||
        m.normalTexture.index >= 0 || m.occlusionTexture.index >= 0 || m.emissiveTexture.index >= 0)
        return true;
    for (const auto& [extension, key] :
         {std::pair{"KHR_materials_transmission", "transmissionTexture"},
          std::pair{"KHR_materials_specular", "specularTexture"},
          std::pair{"KHR_materials_specular", "specularColorTexture"}})
        if (auto it = m.extensions.find(extension); it != m.extensions.end() && it->second.Has(key))
            return true;
    return false;
}

bool GltfMeshes::NormalMapped(const tinygltf::Primitive& prim) const {
    return prim.material >= 0 && size_t(prim.material) < model_.materials.size() &&
           model_.materials[size_t(prim.material)].normalTexture.index >= 0;
}

void GltfMeshes::AddTangents(const tinygltf::Primitive& prim, const std::string& at, int skin,
                             TriangleMesh& mesh) {
    const bool normalMapped = NormalMapped(prim);
    const bool deforms =
        !prim.targets.empty() || (skin >= 0 && prim.attributes.count("JOINTS_0") > 0);
    if (mesh.uvs.empty() || !normalMapped || deforms) return;
    const auto tangent = prim.attributes.find("TANGENT");
    if (tangent == prim.attributes.end()) {
        GenerateTangents(mesh);
        return;
    }
    const std::string field = at + ".attributes.TANGENT";
    std::vector<vec4> tangents;
    try {
        tangents = ReadGltfFloats<4>(doc_, tangent->second, field, TINYGLTF_TYPE_VEC4);
    } catch (const GltfUnsupported& u) {
        doc_.Warn("unsupported:" + u.what,
                  field + ": " + u.what + "; the primitive's tangents are generated instead");
        GenerateTangents(mesh);
        return;
    }
    if (tangents.size() != mesh.positions.size()) doc_.Fail(field, "count differs from POSITION's");
    for (vec4& t : tangents) {
        const float length = glm::length(vec3(t));
        if (!(length > 0.0f)) {
            doc_.Warn("tangent-zero", field +
                                          ": a zero tangent; the primitive's tangents are "
                                          "generated instead");
            GenerateTangents(mesh);
            return;
        }
        t = vec4(vec3(t) / length, t.w < 0.0f ? -1.0f : 1.0f);
    }
    mesh.tangents = std::move(tangents);
}

void GltfMeshes::ReadDeformation(const tinygltf::Primitive& prim, const std::string& at,
                                 size_t mesh, int skin, const TriangleMesh& triangles,
                                 GltfPrimitive& out) {
    auto deformable = std::make_shared<DeformableMesh>();
    deformable->rest = triangles;
    const bool skinned =
        skin >= 0 &&
        ReadGltfSkinInfluences(doc_, prim, at, uint32_t(model_.skins[size_t(skin)].joints.size()),
                               *deformable, out.nodeJoint);
    const bool morphed =
        ReadGltfMorphTargets(doc_, prim, at, model_.meshes[mesh], JsonIndexed("meshes", mesh),
                             *deformable, morphDeltas_);
    if (!skinned && !morphed) return;
    out.deformableMesh = int32_t(out_.scene.AddDeformableMesh(std::move(deformable)));
    summary_.deformingPrimitives++;
}

std::vector<vec3> GltfMeshes::ReadVertexColors(int accessor, const std::string& field,
                                               size_t vertices) {
    AccessorView a;
    try {
        a = GltfAccessor(doc_, accessor, field, {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4});
    } catch (const GltfUnsupported& u) {
        doc_.Warn("unsupported:" + u.what, field + ": " + u.what + "; vertex colours not applied");
        return {};
    }
    // glTF 2.0, 3.7.2.1: floats, or unsigned bytes or shorts, normalised.
    const bool normalisedInteger =
        a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                         a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !normalisedInteger)
        doc_.Fail(JsonIndexed("accessors", size_t(accessor)),
                  "COLOR_0 must be floats or normalized unsigned bytes or shorts");
    if (a.count != vertices) doc_.Fail(field, "count differs from POSITION's");
    std::vector<vec3> colors(a.count);
    size_t outside = 0;
    for (size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = a.Component(i, c);
            if (!FiniteFloat(v))
                doc_.Fail(field, "accessor " + std::to_string(accessor) + ", element " +
                                     std::to_string(i) + ": NaN or infinite");
            if (v < 0.0f || v > 1.0f) ++outside;
            colors[i][c] = std::clamp(v, 0.0f, 1.0f);
        }
    if (outside > 0)
        doc_.Warn("color0-range", field + ": " + std::to_string(outside) +
                                      " components outside [0, 1] (glTF's range for colours) "
                                      "are clamped");
    return colors;
}

// The triangles of a strip or a fan as the glTF specification numbers them (3.7.2.1): strip
// triangle i is (v_i, v_{i+1+i%2}, v_{i+2-i%2}), keeping one winding; fan triangle i is
// (v_{i+1}, v_{i+2}, v_0). Degenerate ones (repeated vertices, as strips use to restart) are left
// out: they cover nothing.
std::vector<glm::uvec3> StripOrFanTriangles(const std::vector<uint32_t>& v, bool fan) {
    std::vector<glm::uvec3> triangles;
    for (size_t i = 0; i + 2 < v.size(); ++i) {
        const glm::uvec3 t = fan ? glm::uvec3(v[i + 1], v[i + 2], v[0])
                                 : glm::uvec3(v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]);
        if (t.x != t.y && t.y != t.z && t.x != t.z) triangles.push_back(t);
    }
    return triangles;
}

TriangleMesh GltfMeshes::ReadPrimitive(const tinygltf::Primitive& prim, const std::string& at) {
    TriangleMesh mesh;
    auto attribute = [&](const char* name) {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    const int position = attribute("POSITION");
    if (position < 0) throw GltfUnsupported{"a primitive without POSITION (compressed?)"};
    mesh.positions =
        ReadGltfFloats<3>(doc_, position, at + ".attributes.POSITION", TINYGLTF_TYPE_VEC3);
    const size_t vertices = mesh.positions.size();
    if (const int color = attribute("COLOR_0"); color >= 0)
        mesh.colors = ReadVertexColors(color, at + ".attributes.COLOR_0", vertices);
    if (const int normal = attribute("NORMAL"); normal >= 0) {
        mesh.normals =
            ReadGltfFloats<3>(doc_, normal, at + ".attributes.NORMAL", TINYGLTF_TYPE_VEC3);
        if (mesh.normals.size() != vertices)
            doc_.Fail(at + ".attributes.NORMAL", "count differs from POSITION's");
        for (vec3& n : mesh.normals) {
            const float length = glm::length(n);
            n = length > 0.0f ? n / length : vec3(0, 1, 0);
        }
    }
    if (const int uv = attribute("TEXCOORD_0"); uv >= 0) {
        mesh.uvs = ReadGltfFloats<2>(doc_, uv, at + ".attributes.TEXCOORD_0", TINYGLTF_TYPE_VEC2);
        if (mesh.uvs.size() != vertices)
            doc_.Fail(at + ".attributes.TEXCOORD_0", "count differs from POSITION's");
    }
    std::vector<uint32_t> indices;
    if (prim.indices >= 0) {
        const AccessorView a =
            GltfAccessor(doc_, prim.indices, at + ".indices", {TINYGLTF_TYPE_SCALAR});
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            doc_.Fail(JsonIndexed("accessors", size_t(prim.indices)) + ".componentType",
                      "indices must be unsigned bytes, shorts or ints");
        indices.resize(a.count);
        for (size_t i = 0; i < a.count; ++i) {
            indices[i] = a.Index(i);
            if (indices[i] >= vertices)
                doc_.Fail(at + ".indices", "index " + std::to_string(i) + " is " +
                                               std::to_string(indices[i]) + ", out of range (" +
                                               std::to_string(vertices) + " vertices)");
        }
    } else {
        indices.resize(vertices);
        for (size_t i = 0; i < vertices; ++i) indices[i] = uint32_t(i);
    }
    if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP || prim.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        mesh.indices = StripOrFanTriangles(indices, prim.mode == TINYGLTF_MODE_TRIANGLE_FAN);
        return mesh;
    }
    if (indices.size() % 3 != 0)
        doc_.Fail(prim.indices >= 0 ? at + ".indices" : at + ".attributes.POSITION",
                  std::to_string(indices.size()) + " indices do not make whole triangles");
    for (size_t i = 0; i < indices.size(); i += 3)
        mesh.indices.push_back({indices[i], indices[i + 1], indices[i + 2]});
    return mesh;
}

}  // namespace rtrt
