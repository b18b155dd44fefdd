// A BLAS's outline (blas_outline.h): its parts hold every primitive, and the instance boxes made
// from them hold every vertex as the instance's transform computes it while taking far less room
// than the corners of the turned box where the shape is thin along the box's diagonal.
#include "engine/bvh/tlas/blas_outline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "engine/bvh/tlas/tlas.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

Aabb PartBox(const BlasOutline& outline, uint32_t k) {
    return {outline.partCentre[k] - outline.partHalf[k],
            outline.partCentre[k] + outline.partHalf[k]};
}

bool InsideSomePart(const BlasOutline& outline, const Aabb& box) {
    for (uint32_t k = 0; k < outline.partCount; ++k)
        if (PartBox(outline, k).Contains(box)) return true;
    return false;
}

// Triangles along the diagonal of the unit cube, each within 0.01 of it.
TriangleMesh DiagonalRod(uint32_t count) {
    TriangleMesh mesh;
    for (uint32_t i = 0; i < count; ++i) {
        const vec3 c(float(i) / float(count - 1));
        mesh.positions.push_back(c);
        mesh.positions.push_back(glm::min(c + vec3(0.01f, 0.0f, 0.0f), vec3(1.0f)));
        mesh.positions.push_back(glm::min(c + vec3(0.0f, 0.01f, 0.0f), vec3(1.0f)));
        mesh.indices.push_back({3 * i, 3 * i + 1, 3 * i + 2});
    }
    return mesh;
}

TEST(BlasOutline, PartsHoldEveryPrimitive) {
    const Blas blas = BuildTriangleBlas(test::RandomTriangles(2000, 3));
    const BlasOutline outline = OutlineOfBlas(blas);
    ASSERT_EQ(outline.partCount, BlasOutline::kMaxParts);
    EXPECT_EQ(outline.sphere.w, 0.0f);
    for (uint32_t slot = 0; slot < blas.PrimCount(); ++slot) {
        ASSERT_TRUE(InsideSomePart(outline, blas.triangles[slot].Bounds())) << "slot " << slot;
    }
    // The parts are nodes of the tree: inside its box but for the ulp their halves were rounded
    // up by.
    const Aabb root{blas.bounds.min - vec3(1e-6f), blas.bounds.max + vec3(1e-6f)};
    for (uint32_t k = 0; k < outline.partCount; ++k)
        EXPECT_TRUE(root.Contains(PartBox(outline, k))) << "part " << k;
}

// The 12 triangles of the cube [-h, h]^3.
TriangleMesh Cube(float h) {
    TriangleMesh mesh;
    for (uint32_t i = 0; i < 8; ++i)
        mesh.positions.push_back(vec3(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h));
    const uint32_t faces[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5},
                                   {0, 4, 5}, {0, 5, 1}, {2, 3, 7}, {2, 7, 6},
                                   {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
    for (const auto& f : faces) mesh.indices.push_back({f[0], f[1], f[2]});
    return mesh;
}

// No parts where the root is a leaf, where the tree deforms, or where the parts' images take no
// less room than the turned box: a cube's faces reach its corners under any turn.
TEST(BlasOutline, NoPartsForALeafRootADeformingTreeOrACube) {
    const Blas cube = BuildTriangleBlas(Cube(0.25f));
    ASSERT_FALSE(cube.nodes[0].IsLeaf());
    EXPECT_EQ(OutlineOfBlas(cube).partCount, 0u);
    const Blas one = BuildTriangleBlas(test::RandomTriangles(1, 1));
    EXPECT_EQ(OutlineOfBlas(one).partCount, 0u);
    const Blas many = BuildTriangleBlas(test::RandomTriangles(100, 2));
    EXPECT_EQ(OutlineOfBlas(many, true).partCount, 0u);
    const Sphere s{vec3(1.0f, 2.0f, 3.0f), 0.5f};
    const BlasOutline ball = OutlineOfBlas(BuildSphereBlas(std::span<const Sphere>(&s, 1)), true);
    EXPECT_EQ(ball.sphere, vec4(1.0f, 2.0f, 3.0f, 0.5f));
    EXPECT_EQ(ball.partCount, 0u);
}

// Turned, stretched (up to 1000:1), shrunk to 1e-6 and moved up to 1e4 away: every vertex as
// ObjectToWorld().Point computes it lies in the instance's box, which is never wider than the
// turned box's corners but for the few float ulps of its rounding margin.
TEST(BlasOutline, InstanceBoxHoldsEveryTransformedVertex) {
    const Blas blas = BuildTriangleBlas(test::RandomTriangles(500, 7));
    const BlasOutline outline = OutlineOfBlas(blas);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), stretch(0.1f, 4.0f);
    for (int trial = 0; trial < 300; ++trial) {
        const int k = trial % 4;
        const float reach = k == 0 ? 1e4f : k == 1 ? 1.0f : 0.0f;
        glm::mat4 m = glm::translate(glm::mat4(1), reach * vec3(u(rng), u(rng), u(rng)));
        m = glm::rotate(m, 3.0f * u(rng), glm::normalize(vec3(u(rng), u(rng), u(rng)) + 0.01f));
        vec3 scale(stretch(rng), stretch(rng), stretch(rng));
        if (k == 2) scale[trial % 3] *= 1000.0f;
        if (k == 3) scale *= 1e-6f;
        m = glm::scale(m, scale);
        const Instance inst = MakeInstance(0, 0, m);
        const Affine toWorld = inst.ObjectToWorld();
        const Aabb box = InstanceWorldBox(inst, blas.bounds, &outline);
        const Aabb corners = TransformBounds(toWorld, blas.bounds);
        SCOPED_TRACE(testing::Message() << "trial " << trial);
        for (const Triangle& t : blas.triangles)
            for (const vec3& v : {t.v0, t.v1, t.v2}) {
                const vec3 p = toWorld.Point(v);
                ASSERT_TRUE(box.Contains(Aabb{p, p}));
            }
        const vec3 magnitude = glm::max(glm::abs(corners.min), glm::abs(corners.max));
        const float margin = 1e-5f * std::max({magnitude.x, magnitude.y, magnitude.z});
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_GE(box.min[axis], corners.min[axis] - margin);
            EXPECT_LE(box.max[axis], corners.max[axis] + margin);
        }
    }
}

// A thin rod along the unit cube's diagonal, turned so that the rod lies along x: the corners of
// the turned cube span sqrt(2) x sqrt(2) across it, the parts a few hundredths.
TEST(BlasOutline, TurnedRodTakesFarLessRoomThanItsCubesCorners) {
    const Blas blas = BuildTriangleBlas(DiagonalRod(400));
    const BlasOutline outline = OutlineOfBlas(blas);
    ASSERT_EQ(outline.partCount, BlasOutline::kMaxParts);
    // Turns (1,1,1) onto +x: about their cross product by the angle between them.
    const vec3 diagonal = glm::normalize(vec3(1.0f));
    const glm::mat4 m = glm::rotate(glm::mat4(1), std::acos(diagonal.x),
                                    glm::normalize(glm::cross(diagonal, vec3(1, 0, 0))));
    const Instance inst = MakeInstance(0, 0, m);
    const Aabb box = InstanceWorldBox(inst, blas.bounds, &outline);
    const Aabb corners = TransformBounds(inst.ObjectToWorld(), blas.bounds);
    EXPECT_NEAR(box.Extent().x, std::sqrt(3.0f), 0.05f);
    EXPECT_NEAR(corners.Extent().y, std::sqrt(2.0f) + 0.1f, 0.15f);
    EXPECT_LT(box.Extent().y, 0.35f);
    EXPECT_LT(box.Extent().z, 0.35f);
    EXPECT_LT(box.Area(), 0.4f * corners.Area());
}

}  // namespace
}  // namespace rtrt
