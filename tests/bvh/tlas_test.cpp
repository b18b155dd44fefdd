// Two-level traversal: a TLAS over instances finds what testing every instance finds.
#include "engine/bvh/tlas/tlas.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <random>

#include "engine/bvh/tlas/dynamic_tlas.h"
#include "engine/bvh/traversal/scene_traversal.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

struct TwoLevel {
    std::vector<Blas> blases;
    std::vector<BlasView> views;
    std::vector<Instance> instances;
    Tlas tlas;

    void Add(uint32_t blas, const glm::mat4& m) {
        Instance inst{};
        SetTransform(inst, m);
        inst.blasId = blas;
        instances.push_back(inst);
    }
    TlasView Build(TlasBuilder builder = TlasBuilder::kSah) {
        std::vector<Aabb> bounds;
        std::vector<BlasOutline> outlines;
        views.clear();
        for (const Blas& b : blases) {
            bounds.push_back(b.bounds);
            outlines.push_back(OutlineOfBlas(b));
            views.push_back(b.View());
        }
        tlas = BuildTlas(instances, bounds, builder, outlines);
        return {tlas.nodes.data(), instances.data(), views.data()};
    }
};

// Closest hit by asking every instance in turn.
bool BruteForce(const TlasView& scene, uint32_t count, const Ray& ray, SceneHit* hit) {
    float tMax = ray.tMax;
    bool found = false;
    for (uint32_t i = 0; i < count; ++i) {
        const Instance& inst = scene.instances[i];
        SceneHit h;
        float t = tMax;
        if (IntersectBlas(scene.blases[inst.blasId], inst, ray, t, &h, nullptr) && h.t < tMax) {
            tMax = h.t;
            *hit = h;
            hit->instance = i;
            found = true;
        }
    }
    return found;
}

// The single loop of the GPU visits what the nested loops visit: same hit, same counts.
void ExpectSingleLoopEqualsNested(const TlasView& scene, const Ray& ray) {
    SceneHit nested{}, single{};
    TraversalStats nestedStats, singleStats;
    const bool n = IntersectScene(scene, ray, &nested, &nestedStats);
    float tMax = ray.tMax;
    const bool s = TraverseTwoLevel<Query::kIntersect>(scene, ray, tMax, &single, &singleStats);
    ASSERT_EQ(n, s);
    if (n) {
        EXPECT_EQ(nested.t, single.t);
        EXPECT_EQ(nested.instance, single.instance);
        EXPECT_EQ(nested.prim, single.prim);
        EXPECT_EQ(nested.b1, single.b1);
        EXPECT_EQ(nested.b2, single.b2);
    }
    EXPECT_EQ(nestedStats.nodesVisited, singleStats.nodesVisited);
    EXPECT_EQ(nestedStats.primsTested, singleStats.primsTested);
    TraversalStats nestedOccluded, singleOccluded;
    const bool na = OccludedScene(scene, ray, &nestedOccluded);
    tMax = ray.tMax;
    EXPECT_EQ(na, TraverseTwoLevel<Query::kOccluded>(scene, ray, tMax, nullptr, &singleOccluded));
    EXPECT_EQ(nestedOccluded.nodesVisited, singleOccluded.nodesVisited);
    EXPECT_EQ(nestedOccluded.primsTested, singleOccluded.primsTested);
}

void ExpectSameAsBruteForce(TwoLevel& world, float spread, uint32_t seed, TlasBuilder builder) {
    SCOPED_TRACE(builder == TlasBuilder::kSah ? "SAH TLAS" : "LBVH TLAS");
    const TlasView scene = world.Build(builder);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    uint32_t hits = 0;
    for (int i = 0; i < 20000; ++i) {
        Ray ray{spread * vec3(u(rng), u(rng), u(rng)), kInfinity, vec3(u(rng), u(rng), u(rng)), 0};
        if (i % 2) {
            const Instance& target = world.instances[i % world.instances.size()];
            ray.dir = target.ObjectToWorld().Point(vec3(0.1f * u(rng))) - ray.origin;
        }
        SceneHit expected{}, got{};
        const bool e = BruteForce(scene, uint32_t(world.instances.size()), ray, &expected);
        const bool g = IntersectScene(scene, ray, &got);
        ASSERT_EQ(e, g) << "ray " << i;
        hits += e;
        if (e) {
            EXPECT_EQ(expected.t, got.t) << "ray " << i;
            EXPECT_EQ(OccludedScene(scene, Ray{ray.origin, got.t * 1.001f, ray.dir, 0}), true);
        }
        ExpectSingleLoopEqualsNested(scene, ray);
    }
    EXPECT_GT(hits, 2000u);
}

TEST(Tlas, ManyTransformedInstancesMatchBruteForce) {
    TwoLevel world;
    world.blases.push_back(BuildTriangleBlas(test::RandomTriangles(200, 1)));
    const Sphere s{vec3(0), 0.8f};
    world.blases.push_back(BuildSphereBlas(std::span<const Sphere>(&s, 1)));
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(-20.0f, 20.0f);
    for (uint32_t i = 0; i < 300; ++i) {
        glm::mat4 m = glm::translate(glm::mat4(1), vec3(u(rng), u(rng), u(rng)));
        m = glm::rotate(m, u(rng), glm::normalize(vec3(u(rng), u(rng), u(rng))));
        m = glm::scale(m, vec3(0.5f + 0.05f * std::abs(u(rng))));
        world.Add(i % 2, m);
    }
    ExpectSameAsBruteForce(world, 25.0f, 3, TlasBuilder::kSah);
    ExpectSameAsBruteForce(world, 25.0f, 3, TlasBuilder::kLbvh);
}

// Ellipsoids: one-sphere BLASes off their origin under rotations and unequal scales, whose world
// boxes come from the sphere (InstanceWorldBox) rather than the corners of its cube.
TEST(Tlas, StretchedSphereInstancesMatchBruteForce) {
    TwoLevel world;
    const Sphere s{vec3(0.3f, -0.2f, 0.5f), 0.6f};
    world.blases.push_back(BuildSphereBlas(std::span<const Sphere>(&s, 1)));
    world.blases.push_back(BuildTriangleBlas(test::RandomTriangles(50, 4)));
    ASSERT_EQ(BlasSphere(world.blases[0]), vec4(s.center, s.radius));
    ASSERT_EQ(BlasSphere(world.blases[1]).w, 0.0f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-15.0f, 15.0f), stretch(0.2f, 2.5f);
    for (uint32_t i = 0; i < 400; ++i) {
        glm::mat4 m = glm::translate(glm::mat4(1), vec3(u(rng), u(rng), u(rng)));
        m = glm::rotate(m, u(rng), glm::normalize(vec3(u(rng), u(rng), u(rng))));
        m = glm::scale(m, vec3(stretch(rng), stretch(rng), stretch(rng)));
        m = glm::rotate(m, u(rng), glm::normalize(vec3(u(rng), u(rng), u(rng))));
        world.Add(i % 5 == 4 ? 1 : 0, m);
    }
    ExpectSameAsBruteForce(world, 20.0f, 6, TlasBuilder::kSah);
    ExpectSameAsBruteForce(world, 20.0f, 6, TlasBuilder::kLbvh);
}

// A BLAS of one sphere, turned and stretched (up to 1000:1, and scales down to 1e-7): its
// instance's box holds the ellipsoid's extreme points along each axis under the transform the
// traversal applies (the stored L^-1, inverted here in long double), is as tight as that
// ellipsoid's box within a few float ulps, and never wider than the box of the cube's corners.
TEST(Tlas, OneSphereInstanceBoxIsTheEllipsoidsBox) {
    const Sphere s{vec3(1.0f, -2.0f, 0.5f), 0.75f};
    const Blas blas = BuildSphereBlas(std::span<const Sphere>(&s, 1));
    const BlasOutline outline = OutlineOfBlas(blas);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), stretch(0.1f, 4.0f);
    std::uniform_int_distribution<int> kind(0, 3);
    for (int trial = 0; trial < 2000; ++trial) {
        const int k = kind(rng);
        const float reach = k == 0 ? 100.0f : k == 1 ? 1.0f : 0.0f;
        glm::mat4 m = glm::translate(glm::mat4(1), reach * vec3(u(rng), u(rng), u(rng)));
        m = glm::rotate(m, 3.0f * u(rng), glm::normalize(vec3(u(rng), u(rng), u(rng)) + 0.01f));
        vec3 scale(stretch(rng), stretch(rng), stretch(rng));
        if (k == 2) scale[trial % 3] *= 1000.0f;  // 1000:1 and more
        if (k == 3) scale *= 1e-6f;
        m = glm::scale(m, scale);
        m = glm::rotate(m, 3.0f * u(rng), glm::normalize(vec3(u(rng), u(rng), u(rng)) + 0.01f));
        const Instance inst = MakeInstance(0, 0, m);
        const Aabb box = InstanceWorldBox(inst, blas.bounds, &outline);
        const Aabb corners = TransformBounds(inst.ObjectToWorld(), blas.bounds);
        using LongVec = glm::vec<3, long double>;
        const LongVec ra(inst.InverseRow(0)), rb(inst.InverseRow(1)), rd(inst.InverseRow(2));
        const LongVec c0 = glm::cross(rb, rd), c1 = glm::cross(rd, ra), c2 = glm::cross(ra, rb);
        const long double det = glm::dot(ra, c0);
        for (int axis = 0; axis < 3; ++axis) {
            SCOPED_TRACE(testing::Message() << "trial " << trial << " axis " << axis);
            const LongVec row = LongVec(c0[axis], c1[axis], c2[axis]) / det;
            const long double c = glm::dot(row, LongVec(s.center)) + inst.Position()[axis];
            const long double half = s.radius * std::sqrt(glm::dot(row, row));
            EXPECT_LE(box.min[axis], c - half);
            EXPECT_GE(box.max[axis], c + half);
            const long double ulps = 4.0L * std::numeric_limits<float>::epsilon() *
                                     (std::abs(c) + std::abs(inst.Position()[axis]) + half);
            EXPECT_GE(box.min[axis], c - half - ulps);
            EXPECT_LE(box.max[axis], c + half + ulps);
            EXPECT_GE(box.min[axis], corners.min[axis]);
            EXPECT_LE(box.max[axis], corners.max[axis]);
        }
        if (::testing::Test::HasFailure()) return;
    }
}

// The builds take the spheres: every leaf's box is InstanceWorldBox's (the SAH TLAS, the LBVH
// and the runtime's DynamicTlas, built and refit), tighter than the corners' for rolled balls.
TEST(Tlas, BuildsBoxBallsByTheirSpheres) {
    const Sphere s{vec3(0.0f), 0.5f};
    const std::vector<Aabb> bounds = {s.Bounds()};
    const Blas blas = BuildSphereBlas(std::span<const Sphere>(&s, 1));
    const std::vector<BlasOutline> spheres = {OutlineOfBlas(blas)};
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Instance> instances;
    for (int i = 0; i < 64; ++i) {
        glm::mat4 m = glm::translate(glm::mat4(1), 10.0f * vec3(u(rng), u(rng), u(rng)));
        m = glm::rotate(m, 3.0f * u(rng), glm::normalize(vec3(u(rng), u(rng), u(rng)) + 0.01f));
        instances.push_back(MakeInstance(0, 0, m));
    }
    const std::vector<Aabb> world = InstanceWorldBounds(instances, bounds, spheres);
    const std::vector<Aabb> cornerBoxes = InstanceWorldBounds(instances, bounds);
    double area = 0.0, cornerArea = 0.0;
    for (size_t i = 0; i < instances.size(); ++i) {
        const Aabb expected = InstanceWorldBox(instances[i], bounds[0], &spheres[0]);
        EXPECT_EQ(world[i].min, expected.min);
        EXPECT_EQ(world[i].max, expected.max);
        area += world[i].Area();
        cornerArea += cornerBoxes[i].Area();
    }
    EXPECT_LT(area, 0.8 * cornerArea);
    const auto expectLeaves = [&](const AlignedVector<BvhNode>& nodes, const char* what) {
        SCOPED_TRACE(what);
        uint32_t leaves = 0;
        for (const BvhNode& node : nodes) {
            if (!node.IsLeaf()) continue;
            ++leaves;
            EXPECT_EQ(node.boundsMin, world[node.leftFirst].min);
            EXPECT_EQ(node.boundsMax, world[node.leftFirst].max);
        }
        EXPECT_EQ(leaves, instances.size());
    };
    expectLeaves(BuildTlas(instances, bounds, TlasBuilder::kSah, spheres).nodes, "SAH");
    expectLeaves(BuildTlas(instances, bounds, TlasBuilder::kLbvh, spheres).nodes, "LBVH");
    DynamicTlas runtime(TlasPolicy{false, 1e30f, 0});
    runtime.Update(instances, bounds, true, spheres);
    expectLeaves(runtime.Tree().nodes, "runtime, built");
    runtime.Update(instances, bounds, false, spheres);
    expectLeaves(runtime.Tree().nodes, "runtime, refit");
}

// All instances at one point and a far outlier: tests/robust/tlas_checks.h.

TEST(Tlas, EmptySceneHitsNothing) {
    TwoLevel world;
    world.blases.push_back(BuildTriangleBlas(test::RandomTriangles(5, 6)));
    const TlasView scene = world.Build();
    SceneHit hit;
    EXPECT_FALSE(IntersectScene(scene, Ray{vec3(0), kInfinity, vec3(0, 0, 1), 0}, &hit));
}

}  // namespace
}  // namespace rtrt
