#pragma once
// TLAS hard cases: all instances at one point, one far outlier, equal Morton codes, each with the
// SAH and the LBVH top level. Expected: traversal equals brute force over every instance
// (traversal_checks.h's criterion; coplanar copies to 8 ulps, see below) for rays aimed at the
// instances, and the outlier is hit where
// the geometry says (a unit sphere 1e6 away, seen from 50 units: t = 49).
#include <gtest/gtest.h>

#include <random>

#include "tests/robust/traversal_checks.h"

namespace rtrt::robust {

// Rebuilds the scene's TLAS with the given builder.
inline void UseTlasBuilder(RenderScene& scene, TlasBuilder builder) {
    std::vector<Aabb> blasBounds;
    for (const auto& blas : scene.blases) blasBounds.push_back(blas->bounds);
    scene.SetTlas(BuildTlas(scene.instances, blasBounds, builder, scene.BlasOutlines()));
}

// Rays from a box of half-size `spread` around `centre`, half random, half aimed at a random
// instance's origin (plus a random offset of up to 3% of the spread).
inline std::vector<Ray> RaysAtInstances(const RenderScene& scene, vec3 centre, float spread,
                                        uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::uniform_int_distribution<size_t> pick(0, scene.instances.size() - 1);
    std::vector<Ray> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        Ray& r = rays[i];
        r = {centre + spread * vec3(u(rng), u(rng), u(rng)), kInfinity,
             vec3(u(rng), u(rng), u(rng)), 0};
        if (i % 2)
            r.dir =
                scene.instances[pick(rng)].ObjectToWorld().Point(vec3(0.03f * spread * u(rng))) -
                r.origin;
    }
    return rays;
}

template <typename Runner>
void ExpectTlasMatchesBruteForce(const Runner& run, RenderScene& scene, vec3 centre, float spread,
                                 const char* what, float relTol = 0.0f) {
    for (TlasBuilder builder : {TlasBuilder::kSah, TlasBuilder::kLbvh}) {
        SCOPED_TRACE(std::string(Runner::kName) + " " + what +
                     (builder == TlasBuilder::kSah ? ", SAH TLAS" : ", LBVH TLAS"));
        UseTlasBuilder(scene, builder);
        const std::vector<Ray> rays = RaysAtInstances(scene, centre, spread, 10000, 5);
        const uint32_t hits = ExpectSameAsBruteForce(rays, run.Scene(scene, rays), relTol);
        EXPECT_GT(hits, 2500u);
    }
}

template <typename Runner>
void CheckTlasDegenerateInputs(const Runner& run) {
    {  // 64 instances at one point (rotated copies) and one unit sphere 1e6 away
        RenderScene scene;
        scene.AddMaterial({});
        const uint32_t mesh =
            AddMeshBlas(scene, SubdividedBox(1, vec3(-1, -0.2f, -0.5f), vec3(1, 0.2f, 0.5f)).mesh);
        const Sphere s{vec3(0), 1.0f};
        const uint32_t ball = AddSphereBlas(scene, std::span(&s, 1));
        for (int i = 0; i < 64; ++i)
            scene.AddInstance(mesh, 0, Placement(vec3(0), 0.1f * float(i), vec3(0, 1, 0)));
        scene.AddInstance(ball, 0, Placement(vec3(1e6f, 0, 0)));
        // The 64 copies share their top and bottom planes: a ray meets the same plane in many
        // copies, at t that differ by a few ulps (each copy's triangle t carries its own rounding,
        // within the triangle test's error bound), while node boxes are entered at the exact
        // plane. Once one copy's hit is found, boxes entered beyond it (widened by 2 gamma(3))
        // are culled, so which copy wins depends on the order: t agrees to 8 ulps (1e-6).
        ExpectTlasMatchesBruteForce(run, scene, vec3(0), 3.0f, "64 at one point + outlier", 1e-6f);
        for (TlasBuilder builder : {TlasBuilder::kSah, TlasBuilder::kLbvh}) {
            UseTlasBuilder(scene, builder);
            const Ray ray{vec3(1e6f, 0, -50), kInfinity, vec3(0, 0, 1), 0};
            const SceneResult r = run.Scene(scene, std::span(&ray, 1))[0];
            ASSERT_TRUE(r.hit) << "the outlier is reachable";
            EXPECT_EQ(r.instance, 64u);
            EXPECT_NEAR(r.t, 49.0f, 16.0f * 1e6f * 0x1p-23f);  // float spacing at 1e6 x 16
        }
    }
    {  // 1024 distinct instances inside one Morton cell: all codes equal, bounds all differ
        RenderScene scene;
        scene.AddMaterial({});
        const Sphere s{vec3(0), 1e-4f};
        const uint32_t ball = AddSphereBlas(scene, std::span(&s, 1));
        const uint32_t box = AddMeshBlas(scene, SubdividedBox(1, vec3(-1e-4f), vec3(1e-4f)).mesh);
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(0.0f, 1e-3f);
        for (int i = 0; i < 1024; ++i)
            scene.AddInstance(i % 2 ? ball : box, 0, Placement(vec3(u(rng), u(rng), u(rng))));
        // Two far corners make the scene 1e3 wide: the cluster is 1e-6 of it, one Morton cell.
        scene.AddInstance(ball, 0, Placement(vec3(-500.0f)));
        scene.AddInstance(ball, 0, Placement(vec3(500.0f)));
        ExpectTlasMatchesBruteForce(run, scene, vec3(5e-4f), 2e-3f, "equal Morton codes");
    }
}

}  // namespace rtrt::robust
