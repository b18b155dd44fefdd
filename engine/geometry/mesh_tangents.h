#pragma once
// Vertex tangents for normal maps on meshes that bring none (glTF primitives without TANGENT), in
// MikkTSpace's manner: each triangle's dp/du and dp/dv, weighted by the angle at each corner,
// summed per vertex and per handedness, made perpendicular to the vertex normal. A vertex shared
// by triangles whose uvs are mirrored against each other is split in two, so that each side keeps
// its own frame instead of an average of opposite ones.
#include <cmath>
#include <utility>
#include <vector>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

namespace mesh_tangents_detail {

// The angle at corner p0 of triangle (p0, p1, p2); 0 for a degenerate corner.
inline float CornerAngle(vec3 p0, vec3 p1, vec3 p2) {
    const vec3 a = p1 - p0, b = p2 - p0;
    const float la = glm::length(a), lb = glm::length(b);
    if (!(la > 0.0f) || !(lb > 0.0f)) return 0.0f;
    return std::acos(glm::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f));
}

// Any unit vector perpendicular to unit n.
inline vec3 Perpendicular(vec3 n) {
    const vec3 axis = std::fabs(n.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0);
    return glm::normalize(glm::cross(n, axis));
}

}  // namespace mesh_tangents_detail

// Sets mesh.tangents, one per vertex (xyz the unit tangent along increasing u, w = -1 where the
// bitangent cross(normal, xyz) points towards increasing v, the image's down, else +1: the map's
// +y is the image's up, as glTF files' TANGENTs have it). Vertices with both handednesses are
// split (appended, with their normals and uvs), and their mirrored triangles re-indexed. Needs
// uvs; the normals are the mesh's, or the angle-weighted face normals where it has none.
inline void GenerateTangents(TriangleMesh& mesh) {
    using namespace mesh_tangents_detail;
    const size_t vertices = mesh.positions.size();
    // Per vertex and handedness (0: right-handed, 1: mirrored): sums of dp/du, dp/dv and the
    // face normal, angle-weighted.
    struct Sum {
        vec3 dpdu{0.0f}, dpdv{0.0f}, normal{0.0f};
        bool used = false;
    };
    std::vector<Sum> sums(2 * vertices);
    std::vector<uint8_t> faceMirrored(mesh.indices.size(), 0);
    for (size_t f = 0; f < mesh.indices.size(); ++f) {
        const glm::uvec3 t = mesh.indices[f];
        const vec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
        const vec2 uv[3] = {mesh.uvs[t.x], mesh.uvs[t.y], mesh.uvs[t.z]};
        const vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
        const vec2 d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
        const float det = d1.x * d2.y - d2.x * d1.y;
        const vec3 ng = glm::cross(e1, e2);
        vec3 dpdu(0.0f), dpdv(0.0f);
        if (std::fabs(det) > 0.0f && std::isfinite(1.0f / det)) {
            dpdu = (e1 * d2.y - e2 * d1.y) / det;
            dpdv = (e2 * d1.x - e1 * d2.x) / det;
        }
        const uint8_t mirrored = glm::dot(glm::cross(ng, dpdu), dpdv) > 0.0f ? 1 : 0;
        faceMirrored[f] = mirrored;
        const vec3 unitNormal = glm::length(ng) > 0.0f ? glm::normalize(ng) : vec3(0.0f);
        for (int c = 0; c < 3; ++c) {
            const float angle = CornerAngle(p[c], p[(c + 1) % 3], p[(c + 2) % 3]);
            Sum& s = sums[2 * size_t(t[c]) + mirrored];
            s.dpdu += angle * dpdu;
            s.dpdv += angle * dpdv;
            s.normal += angle * unitNormal;
            s.used = true;
        }
    }
    // The mirrored side of a vertex used both ways becomes a new vertex.
    std::vector<uint32_t> mirroredCopy(vertices, 0);
    for (size_t v = 0; v < vertices; ++v) {
        if (!(sums[2 * v].used && sums[2 * v + 1].used)) continue;
        mirroredCopy[v] = uint32_t(mesh.positions.size());
        mesh.positions.push_back(mesh.positions[v]);
        if (!mesh.normals.empty()) mesh.normals.push_back(mesh.normals[v]);
        mesh.uvs.push_back(mesh.uvs[v]);
        if (!mesh.colors.empty()) mesh.colors.push_back(mesh.colors[v]);
    }
    std::vector<vec4> tangents(mesh.positions.size(), vec4(1, 0, 0, 1));
    auto frame = [&](const Sum& s, vec3 normal) {
        vec3 n = normal;
        if (!(glm::length(n) > 0.0f)) n = glm::length(s.normal) > 0.0f ? s.normal : vec3(0, 0, 1);
        n = glm::normalize(n);
        vec3 t = s.dpdu - n * glm::dot(n, s.dpdu);
        t = glm::length(t) > 0.0f ? glm::normalize(t) : Perpendicular(n);
        const float w = glm::dot(glm::cross(n, t), s.dpdv) > 0.0f ? -1.0f : 1.0f;
        return vec4(t, w);
    };
    for (size_t v = 0; v < vertices; ++v)
        for (int h = 0; h < 2; ++h) {
            const Sum& s = sums[2 * v + size_t(h)];
            if (!s.used) continue;
            const uint32_t target = h == 1 && mirroredCopy[v] ? mirroredCopy[v] : uint32_t(v);
            tangents[target] = frame(s, mesh.normals.empty() ? vec3(0.0f) : mesh.normals[v]);
        }
    for (size_t f = 0; f < mesh.indices.size(); ++f) {
        if (!faceMirrored[f]) continue;
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = mesh.indices[f][c];
            if (v < vertices && mirroredCopy[v]) mesh.indices[f][c] = mirroredCopy[v];
        }
    }
    mesh.tangents = std::move(tangents);
}

}  // namespace rtrt
