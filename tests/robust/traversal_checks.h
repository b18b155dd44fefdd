#pragma once
// Two-level BVH traversal equals brute force (every primitive of every instance tested) on
// millions of rays: random rays, rays aimed exactly at vertices and at points of edges, and
// axis-aligned rays with +-0 components that run through vertices, so that they lie in the faces
// of flat and non-flat node boxes. Expected, per ray: the same hit or miss; on a hit the same t
// bit for bit (both call the same primitive test; a tie between two primitives sharing an edge
// may report either, so the reported primitive alone must give that t); the any-hit query
// agrees with the closest-hit query, with the ray's tMax and with tMax cut to just past the hit.
// Also: NaN and infinite rays hit nothing and return.
#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <random>

#include "tests/robust/cases.h"
#include "tests/robust/closed_meshes.h"
#include "tests/robust/scene_builder.h"
#include "tests/test_util.h"

namespace rtrt::robust {

// A small scene of every kind of geometry, with few primitives so brute force stays cheap:
// rotated closed meshes, axis-aligned flat grids (zero-thickness node boxes), a grid standing on
// its edge, spheres from 1e-3 to 1 in radius, one instance scaled unevenly.
inline RenderScene TraversalScene() {
    RenderScene scene;
    scene.AddMaterial({});
    const uint32_t sphereMesh = AddMeshBlas(scene, UvSphere(6, 4, 0.8f, vec3(0)).mesh);
    const uint32_t box = AddMeshBlas(scene, SubdividedBox(1, vec3(-0.5f), vec3(0.5f)).mesh);
    const uint32_t grid = AddMeshBlas(scene, test::GridMesh(2));
    const Sphere spheres[] = {{vec3(0), 1.0f},
                              {vec3(1.5f, 0, 0), 0.25f},
                              {vec3(0, 1.2f, 0), 1e-3f},
                              {vec3(-1, -1, 0.5f), 0.1f},
                              {vec3(0.4f, 0.4f, 0.4f), 0.3f}};
    const uint32_t balls = AddSphereBlas(scene, spheres);
    scene.AddInstance(sphereMesh, 0, Placement(vec3(0), 0.4f, vec3(1, 1, 0)));
    scene.AddInstance(box, 0, Placement(vec3(2, 0.5f, -1), 0.9f, vec3(0, 1, 1)));
    scene.AddInstance(box, 0, Placement(vec3(-2, 0.5f, 0)));  // axis-aligned, shares grid planes
    scene.AddInstance(grid, 0, Placement(vec3(0, -1, 0)));    // flat in y
    scene.AddInstance(grid, 0, Placement(vec3(0, 0, -2), kPi / 2, vec3(1, 0, 0)));  // flat-ish in z
    scene.AddInstance(balls, 0, Placement(vec3(-1, 2, 1)));
    scene.AddInstance(balls, 0, glm::scale(Placement(vec3(2, -2, 2)), vec3(1.0f, 0.25f, 2.0f)));
    scene.BuildTlas();
    return scene;
}

// World-space triangle vertices and sphere centres: the points the aimed rays pass through.
inline std::vector<std::array<vec3, 3>> WorldTriangles(const RenderScene& scene) {
    std::vector<std::array<vec3, 3>> out;
    for (const Instance& inst : scene.instances) {
        const Blas& blas = *scene.blases[inst.blasId];
        for (const Triangle& t : blas.triangles)
            out.push_back({inst.ObjectToWorld().Point(t.v0), inst.ObjectToWorld().Point(t.v1),
                           inst.ObjectToWorld().Point(t.v2)});
        for (const Sphere& s : blas.spheres) {
            const vec3 c = inst.ObjectToWorld().Point(s.center);
            out.push_back({c, c, c});
        }
    }
    return out;
}

inline std::vector<Ray> TraversalRays(const RenderScene& scene, uint32_t count, uint32_t seed) {
    const std::vector<std::array<vec3, 3>> tris = WorldTriangles(scene);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), s(-1.0f, 1.0f);
    std::uniform_int_distribution<size_t> pick(0, tris.size() - 1);
    auto origin = [&] { return 5.0f * vec3(s(rng), s(rng), s(rng)); };
    std::vector<Ray> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        Ray& r = rays[i];
        r = {origin(), kInfinity, vec3(0), 0};
        const auto& tri = tris[pick(rng)];
        switch (i % 4) {
            case 0:  // random
                r.dir = vec3(s(rng), s(rng), s(rng));
                break;
            case 1:  // at a vertex
                r.dir = tri[i / 4 % 3] - r.origin;
                break;
            case 2: {  // at a point of an edge
                const vec3 a = tri[i / 4 % 3], b = tri[(i / 4 + 1) % 3];
                r.dir = a + u(rng) * (b - a) - r.origin;
                break;
            }
            default: {  // along an axis through a vertex, other components +0 or -0
                const int axis = int(i / 4 % 3);
                const float sign = u(rng) < 0.5f ? 1.0f : -1.0f;
                r.dir = vec3(u(rng) < 0.5f ? 0.0f : -0.0f);
                r.dir[axis] = sign;
                r.origin = tri[i / 12 % 3];
                r.origin[axis] -= sign * 6.0f;
            }
        }
    }
    return rays;
}

// Compares every ray's results; returns the number of hits. relTol = 0: t bit for bit.
inline uint32_t ExpectSameAsBruteForce(std::span<const Ray> rays,
                                       std::span<const SceneResult> results, float relTol = 0.0f) {
    uint32_t mismatches = 0, hits = 0;
    auto close = [&](float a, float b) { return a == b || std::abs(a - b) <= relTol * b; };
    for (size_t i = 0; i < rays.size(); ++i) {
        const SceneResult& r = results[i];
        hits += r.bruteHit;
        const bool same = r.hit == r.bruteHit && r.binaryHit == r.bruteHit &&
                          r.occluded == r.bruteHit && r.occludedNear == r.hitNear &&
                          (!r.bruteHit || (close(r.t, r.bruteT) && close(r.binaryT, r.bruteT) &&
                                           r.recheckT == r.t));
        if (!same && ++mismatches <= 5) {
            const Ray& ray = rays[i];
            ADD_FAILURE() << "ray " << i << " o=(" << ray.origin.x << "," << ray.origin.y << ","
                          << ray.origin.z << ") d=(" << ray.dir.x << "," << ray.dir.y << ","
                          << ray.dir.z << "): BVH " << r.hit << " t=" << r.t << ", binary "
                          << r.binaryHit << " t=" << r.binaryT << ", brute force " << r.bruteHit
                          << " t=" << r.bruteT << ", recheck " << r.recheckT << ", any-hit "
                          << r.occluded << ", near " << r.occludedNear << "/" << r.hitNear;
        }
    }
    EXPECT_EQ(mismatches, 0u) << "of " << rays.size() << " rays";
    return hits;
}

template <typename Runner>
void CheckTraversalMatchesBruteForce(const Runner& run, uint32_t rayCount) {
    SCOPED_TRACE(Runner::kName);
    const RenderScene scene = TraversalScene();
    const std::vector<Ray> rays = TraversalRays(scene, rayCount, 2024);
    const std::vector<SceneResult> results = run.Scene(scene, rays);
    const uint32_t hits = ExpectSameAsBruteForce(rays, results);
    // Aimed rays hit (3/4 of them aim at geometry): the comparison is not about empty space.
    EXPECT_GT(hits, rayCount / 2);
}

// Rays that are not traceable hit nothing, cast no shadow and return; odd but finite rays
// (denormal or huge directions, far origins) agree with brute force.
template <typename Runner>
void CheckBadRays(const Runner& run) {
    SCOPED_TRACE(Runner::kName);
    const RenderScene scene = TraversalScene();
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = kInfinity;
    const std::vector<Ray> bad = {
        {vec3(0, 0, 10), inf, vec3(nan, 0, -1), 0},   {vec3(nan, 0, 10), inf, vec3(0, 0, -1), 0},
        {vec3(0, 0, 10), nan, vec3(0, 0, -1), 0},     {vec3(0, 0, 10), inf, vec3(nan), 0},
        {vec3(inf, 0, 10), inf, vec3(0, 0, -1), 0},   {vec3(0, 0, 10), inf, vec3(0, 0, -inf), 0},
        {vec3(0, 0, 10), inf, vec3(-inf, inf, 1), 0}, {vec3(0, 0, 10), inf, vec3(0), 0},
        {vec3(0, 0, 10), inf, vec3(-0.0f), 0},        {vec3(-inf), inf, vec3(inf), 0},
    };
    const std::vector<SceneResult> badResults = run.Scene(scene, bad);
    for (size_t i = 0; i < bad.size(); ++i) {
        EXPECT_FALSE(badResults[i].hit || badResults[i].binaryHit || badResults[i].occluded)
            << "bad ray " << i;
    }
    const std::vector<Ray> odd = {
        {vec3(0.1f, 0.1f, 10), inf, vec3(0, 0, -1e-30f), 0},       // tiny direction: t = 1e31
        {vec3(0.1f, 0.1f, 10), inf, vec3(1e-41f, 0, -1e-40f), 0},  // denormal: t beyond float
        {vec3(0, 0, 10), inf, vec3(0, 1e-38f, -3e38f), 0},         // huge direction
        {vec3(0, 0, 1e30f), inf, vec3(0, 0, -1), 0},               // far origin
        {vec3(1e30f, 1e30f, 1e30f), inf, vec3(-1, -1, -1), 0},
        {vec3(0, 0, 10), -1.0f, vec3(0, 0, -1), 0},  // negative tMax
        {vec3(0, 0, 10), 0.0f, vec3(0, 0, -1), 0},   // zero tMax
    };
    const std::vector<SceneResult> oddResults = run.Scene(scene, odd);
    ExpectSameAsBruteForce(odd, oddResults);
    EXPECT_TRUE(oddResults[0].hit) << "a tiny direction still points at the scene";
    EXPECT_FALSE(oddResults[5].hit || oddResults[6].hit) << "nothing lies in t <= 0";
}

}  // namespace rtrt::robust
