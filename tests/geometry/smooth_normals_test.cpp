// Vertex normals of meshes that bring none, at any size a float holds.
#include "engine/geometry/smooth_normals.h"

#include <gtest/gtest.h>

namespace rtrt {
namespace {

TriangleMesh RightTriangle(float edge) {
    TriangleMesh mesh;
    mesh.positions = {vec3(0.0f), vec3(edge, 0.0f, 0.0f), vec3(0.0f, edge, 0.0f)};
    mesh.indices = {glm::uvec3(0, 1, 2)};
    return mesh;
}

// The cross product of edges of 1e10 overflowed a float's square, and one of 1e-15 underflowed it:
// every vertex had got the fallback +y instead of the face's +z.
TEST(SmoothNormals, TrianglesOfAnySizeGetTheirFacesNormal) {
    for (float edge : {1e-30f, 1e-15f, 1e-3f, 1.0f, 3e9f, 1e10f, 1e19f, 1e30f}) {
        SCOPED_TRACE(edge);
        TriangleMesh mesh = RightTriangle(edge);
        ComputeSmoothNormals(mesh);
        ASSERT_EQ(mesh.normals.size(), 3u);
        for (const vec3& n : mesh.normals) EXPECT_EQ(n, vec3(0.0f, 0.0f, 1.0f));
    }
}

// Meshes of ordinary size keep the area weighting bit for bit; a vertex on no triangle gets +y.
TEST(SmoothNormals, AreaWeightsAndUnusedVertices) {
    TriangleMesh mesh;
    // A small triangle facing +z and a large one facing +x share vertex 0.
    mesh.positions = {vec3(0.0f),    vec3(1, 0, 0), vec3(0, 1, 0),
                      vec3(0, 3, 0), vec3(0, 0, 3), vec3(7.0f)};
    mesh.indices = {glm::uvec3(0, 1, 2), glm::uvec3(0, 3, 4)};
    ComputeSmoothNormals(mesh);
    const vec3 sum(9.0f, 0.0f, 1.0f);
    EXPECT_EQ(mesh.normals[0], sum / glm::length(sum));
    EXPECT_EQ(mesh.normals[1], vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(mesh.normals[3], vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(mesh.normals[5], vec3(0.0f, 1.0f, 0.0f));
}

}  // namespace
}  // namespace rtrt
