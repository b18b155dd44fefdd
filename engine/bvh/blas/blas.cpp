#include "engine/bvh/blas/blas.h"

#include <algorithm>

#include "engine/bvh/build/spatial_split_builder.h"
#include "engine/core/parallel_for.h"

namespace rtrt {

BlasView Blas::View() const {
    BlasView view;
    view.nodes = nodes.data();
    view.nodes4 = nodes4.empty() ? nullptr : nodes4.data();
    view.triangles = triangles.data();
    view.normals = normals.empty() ? nullptr : normals.data();
    view.spheres = spheres.data();
    view.kind = kind;
    view.primCount = PrimCount();
    view.uvs = uvs.empty() ? nullptr : uvs.data();
    view.tangents = tangents.empty() ? nullptr : tangents.data();
    view.colors = colors.empty() ? nullptr : colors.data();
    return view;
}

size_t Blas::Bytes() const {
    return nodes.size() * sizeof(BvhNode) + nodes4.size() * sizeof(Bvh4Node) +
           triangles.size() * sizeof(Triangle) + normals.size() * sizeof(TriangleNormals) +
           spheres.size() * sizeof(Sphere) + uvs.size() * sizeof(TriangleUvs) +
           tangents.size() * sizeof(TriangleTangents) + colors.size() * sizeof(TriangleColors);
}

uint32_t Blas::SourcePrimCount() const {
    uint32_t count = 0;
    for (uint32_t id : primIds) count = std::max(count, id + 1);
    return count;
}

size_t Blas::DeviceBytes() const { return Bytes() - nodes4.size() * sizeof(Bvh4Node); }

DeformableMesh RestMeshOfBlas(const Blas& blas) {
    DeformableMesh mesh;
    const size_t n = blas.triangles.size();
    TriangleMesh& rest = mesh.rest;
    rest.positions.resize(3 * n);
    // A triangle in several leaves (spatial splits) is one source triangle: it takes the
    // vertices of its first slot, and the other slots' copies are never drawn from.
    rest.indices.resize(blas.SourcePrimCount());
    for (size_t s = n; s-- > 0;) {
        const uint32_t v = uint32_t(3 * s);
        rest.indices[blas.primIds[s]] = glm::uvec3(v, v + 1, v + 2);
    }
    if (!blas.normals.empty()) rest.normals.resize(3 * n);
    if (!blas.uvs.empty()) rest.uvs.resize(3 * n);
    if (!blas.colors.empty()) rest.colors.resize(3 * n);
    ParallelFor(0, n, 4096, [&](size_t s) {
        const uint32_t v = uint32_t(3 * s);
        const Triangle& t = blas.triangles[s];
        rest.positions[v] = t.v0;
        rest.positions[v + 1] = t.v1;
        rest.positions[v + 2] = t.v2;
        if (!blas.normals.empty()) {
            rest.normals[v] = UnpackNormal(blas.normals[s].n0);
            rest.normals[v + 1] = UnpackNormal(blas.normals[s].n1);
            rest.normals[v + 2] = UnpackNormal(blas.normals[s].n2);
        }
        if (!blas.uvs.empty()) {
            rest.uvs[v] = blas.uvs[s].uv0;
            rest.uvs[v + 1] = blas.uvs[s].uv1;
            rest.uvs[v + 2] = blas.uvs[s].uv2;
        }
        if (!blas.colors.empty())
            for (int k = 0; k < 3; ++k) rest.colors[v + k] = blas.colors[s].Corner(k);
    });
    return mesh;
}

Blas BuildTriangleBlas(const TriangleMesh& mesh, const BvhBuildOptions& options) {
    const size_t count = mesh.indices.size();
    auto triangle = [&](size_t i) {
        const glm::uvec3 idx = mesh.indices[i];
        return Triangle{mesh.positions[idx.x], mesh.positions[idx.y], mesh.positions[idx.z]};
    };
    Bvh bvh;
    if (options.builder == BvhBuilder::kSpatialSah) {
        std::vector<Triangle> triangles(count);
        ParallelFor(0, count, 4096, [&](size_t i) { triangles[i] = triangle(i); });
        bvh = BuildSpatialSplitBvh(triangles, options);
    } else {
        std::vector<Aabb> bounds(count);
        ParallelFor(0, count, 4096, [&](size_t i) { bounds[i] = triangle(i).Bounds(); });
        bvh = BuildBvh(bounds, options);
    }
    // A spatial-split tree may hold a triangle in several leaves: one slot each.
    const size_t slots = bvh.primOrder.size();

    // Triangles go straight from the mesh into leaf order: no intermediate copy.
    Blas blas;
    blas.kind = GeometryKind::kTriangles;
    blas.nodes = std::move(bvh.nodes);
    blas.primIds = std::move(bvh.primOrder);
    blas.triangles.resize(slots);
    const bool smooth = !mesh.normals.empty();
    if (smooth) blas.normals.resize(slots);
    const bool textured = !mesh.uvs.empty();
    if (textured) blas.uvs.resize(slots);
    const bool tangents = !mesh.tangents.empty();
    if (tangents) blas.tangents.resize(slots);
    const bool colored = !mesh.colors.empty();
    if (colored) blas.colors.resize(slots);
    ParallelFor(0, slots, 4096, [&](size_t slot) {
        const uint32_t prim = blas.primIds[slot];
        blas.triangles[slot] = triangle(prim);
        if (smooth) {
            const glm::uvec3 idx = mesh.indices[prim];
            blas.normals[slot] = TriangleNormals::Pack(mesh.normals[idx.x], mesh.normals[idx.y],
                                                       mesh.normals[idx.z]);
        }
        if (textured) {
            const glm::uvec3 idx = mesh.indices[prim];
            blas.uvs[slot] = {mesh.uvs[idx.x], mesh.uvs[idx.y], mesh.uvs[idx.z]};
        }
        if (tangents) {
            const glm::uvec3 idx = mesh.indices[prim];
            blas.tangents[slot] = {mesh.tangents[idx.x], mesh.tangents[idx.y],
                                   mesh.tangents[idx.z]};
        }
        if (colored) {
            const glm::uvec3 idx = mesh.indices[prim];
            blas.colors[slot] =
                TriangleColors::Pack(mesh.colors[idx.x], mesh.colors[idx.y], mesh.colors[idx.z]);
        }
    });
    blas.nodes4 = CollapseToBvh4(blas.nodes);
    blas.bounds = blas.nodes[0].Bounds();
    return blas;
}

Blas BuildSphereBlas(std::span<const Sphere> spheres, const BvhBuildOptions& options) {
    std::vector<Aabb> bounds(spheres.size());
    for (size_t i = 0; i < spheres.size(); ++i) bounds[i] = spheres[i].Bounds();
    Bvh bvh = BuildBvh(bounds, options);
    Blas blas;
    blas.kind = GeometryKind::kSpheres;
    blas.nodes = std::move(bvh.nodes);
    blas.primIds = std::move(bvh.primOrder);
    blas.spheres.resize(spheres.size());
    for (size_t slot = 0; slot < spheres.size(); ++slot)
        blas.spheres[slot] = spheres[blas.primIds[slot]];
    blas.bounds = blas.nodes[0].Bounds();
    return blas;
}

void ScaleAndMoveBlas(Blas& blas, vec3 centre, float scale) {
    auto move = [&](vec3 p) { return (p - centre) * scale; };
    ParallelFor(0, blas.triangles.size(), 4096, [&](size_t i) {
        Triangle& t = blas.triangles[i];
        t = {move(t.v0), move(t.v1), move(t.v2)};
    });
    for (BvhNode& node : blas.nodes) node.SetBounds({move(node.boundsMin), move(node.boundsMax)});
    for (Bvh4Node& node : blas.nodes4) {
        for (int i = 0; i < 4; ++i) {
            const vec3 lo = move({node.minX[i], node.minY[i], node.minZ[i]});
            const vec3 hi = move({node.maxX[i], node.maxY[i], node.maxZ[i]});
            node.minX[i] = lo.x, node.minY[i] = lo.y, node.minZ[i] = lo.z;
            node.maxX[i] = hi.x, node.maxY[i] = hi.y, node.maxZ[i] = hi.z;
        }
    }
    blas.bounds = blas.nodes[0].Bounds();
}

}  // namespace rtrt
