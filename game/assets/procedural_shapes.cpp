#include "game/assets/procedural_shapes.h"

namespace rtrt {
namespace {

void AddQuad(TriangleMesh& mesh, vec3 a, vec3 b, vec3 c, vec3 d) {
    const uint32_t base = uint32_t(mesh.positions.size());
    const vec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (vec3 p : {a, b, c, d}) {
        mesh.positions.push_back(p);
        mesh.normals.push_back(n);
    }
    mesh.indices.push_back({base, base + 1, base + 2});
    mesh.indices.push_back({base, base + 2, base + 3});
}

}  // namespace

TriangleMesh MakeBoxMesh(vec3 size) {
    TriangleMesh mesh;
    const vec3 h = 0.5f * size;
    // Each face counter-clockwise seen from outside.
    AddQuad(mesh, {h.x, -h.y, -h.z}, {h.x, h.y, -h.z}, {h.x, h.y, h.z}, {h.x, -h.y, h.z});
    AddQuad(mesh, {-h.x, -h.y, h.z}, {-h.x, h.y, h.z}, {-h.x, h.y, -h.z}, {-h.x, -h.y, -h.z});
    AddQuad(mesh, {-h.x, h.y, -h.z}, {-h.x, h.y, h.z}, {h.x, h.y, h.z}, {h.x, h.y, -h.z});
    AddQuad(mesh, {-h.x, -h.y, h.z}, {-h.x, -h.y, -h.z}, {h.x, -h.y, -h.z}, {h.x, -h.y, h.z});
    AddQuad(mesh, {-h.x, -h.y, h.z}, {h.x, -h.y, h.z}, {h.x, h.y, h.z}, {-h.x, h.y, h.z});
    AddQuad(mesh, {h.x, -h.y, -h.z}, {-h.x, -h.y, -h.z}, {-h.x, h.y, -h.z}, {h.x, h.y, -h.z});
    return mesh;
}

TriangleMesh MakePlaneMesh(float sizeX, float sizeZ) {
    TriangleMesh mesh;
    const float x = 0.5f * sizeX, z = 0.5f * sizeZ;
    AddQuad(mesh, {-x, 0, z}, {x, 0, z}, {x, 0, -z}, {-x, 0, -z});
    return mesh;
}

void FitMesh(TriangleMesh& mesh, float extent) {
    const Aabb bounds = mesh.Bounds();
    const float largest = MaxComponent(bounds.Extent());
    if (bounds.IsEmpty() || largest <= 0.0f) return;
    const float scale = extent / largest;
    const vec3 centre = bounds.Centroid();
    for (vec3& p : mesh.positions) p = (p - centre) * scale;
}

void FitBlas(Blas& blas, const Aabb& sourceBounds, float extent) {
    const float largest = MaxComponent(sourceBounds.Extent());
    if (sourceBounds.IsEmpty() || largest <= 0.0f) return;
    ScaleAndMoveBlas(blas, sourceBounds.Centroid(), extent / largest);
}

}  // namespace rtrt
