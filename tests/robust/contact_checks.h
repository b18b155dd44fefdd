#pragma once
// Near contact: surfaces closer than the float triangle test's error bound on t (1e-5 for a unit
// triangle seen by a ray whose dominant axis is not the normal's), and huge ground spheres. The
// hits within that bound are decided in double (triangle_intersect.h), spheres are intersected
// and their points placed in double (sphere_intersect.h, surface.h). Expected values:
// - a ray starting a gap g (1e-5, 4e-6) off a unit-sized surface, aimed at it, hits it, at the
//   distance the double-precision plane gives for the very float origin, the hit point within
//   2e-7 of the plane (1e-7 of the square's size: the float test's t is accurate to its error
//   bound, when it is not decided in double; grazing rays stretch that along the ray);
// - a shadow ray from the receiver under an occluder g above it (primary rays from inside the
//   gap, g / 2 off the receiver) is occluded by the occluder, from
//   every light direction of the hemisphere (elevations 1 to 89 degrees, every dominant axis);
//   the shadow ray's side exit through the gap needs a lateral run of more than 0.25 units, which
//   at g / tan(elevation) <= 6e-4 it never reaches;
// - a small box (0.05) on a ground sphere of radius 1e5 or 1e6, or on a plane, shadows exactly the
//   ground points whose ray toward the light meets the box in double (points whose answer
//   changes when the box grows or shrinks by 1e-4 are skipped), and no ground point shadows
//   itself.
#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <string>

#include "tests/robust/cases.h"
#include "tests/robust/scene_builder.h"

namespace rtrt::robust {

// A square of half-size h, two triangles, centred on `centre` in the plane with normal n.
inline TriangleMesh Square(vec3 centre, vec3 n, float h) {
    n = glm::normalize(n);
    const vec3 u = Perpendicular(n);
    const vec3 v = glm::cross(n, u);
    TriangleMesh m;
    for (vec3 c : {-u - v, u - v, u + v, -u + v}) m.positions.push_back(centre + h * c);
    m.indices = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

// Distance along d from o to the plane through the mesh's first triangle, in double.
inline double PlaneDistance(const TriangleMesh& m, vec3 o, vec3 d) {
    const glm::dvec3 v0(m.positions[0]), v1(m.positions[1]), v2(m.positions[2]);
    const glm::dvec3 n = glm::cross(v1 - v0, v2 - v0);
    return glm::dot(n, v0 - glm::dvec3(o)) / glm::dot(n, glm::dvec3(d));
}

// A unit direction at `elevation` above the plane of n and `azimuth` around it.
inline vec3 Hemisphere(vec3 n, float elevation, float azimuth) {
    const vec3 u = Perpendicular(n), v = glm::cross(n, u);
    return glm::normalize(std::sin(elevation) * n +
                          std::cos(elevation) * (std::cos(azimuth) * u + std::sin(azimuth) * v));
}

inline const vec3 kContactNormal = glm::normalize(vec3(0.2f, 1.0f, -0.35f));
inline const vec3 kContactCentre(0.3f, -0.2f, 0.1f);

template <typename Runner>
void CheckRaysStartingNearASurfaceFindIt(const Runner& run) {
    const vec3 n = kContactNormal;
    const TriangleMesh square = Square(kContactCentre, n, 1.0f);
    RenderScene scene;
    scene.AddMaterial({});
    scene.AddInstance(AddMeshBlas(scene, square), 0, glm::mat4(1.0f));
    scene.BuildTlas();
    const vec3 u = Perpendicular(n), v = glm::cross(n, u);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (float gap : {1e-5f, 4e-6f}) {
        SCOPED_TRACE(std::string(Runner::kName) + " gap " + std::to_string(gap));
        std::vector<Ray> rays;
        for (int i = 0; i < 4096; ++i) {
            const float side = i % 2 ? 1.0f : -1.0f;  // either face
            const vec3 at =
                kContactCentre + 1.6f * (unit(rng) - 0.5f) * u + 1.6f * (unit(rng) - 0.5f) * v;
            // Up to 80 degrees off the normal, toward the surface.
            const vec3 away = Hemisphere(side * n, 0.175f + 1.4f * unit(rng), 6.2832f * unit(rng));
            rays.push_back({at + side * gap * n, kInfinity, -away, 0.0f});
        }
        const std::vector<SceneResult> results = run.Scene(scene, rays);
        uint32_t missed = 0, wrongT = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            const double expected = PlaneDistance(square, rays[i].origin, rays[i].dir);
            ASSERT_GT(expected, 0.0) << "case " << i << " starts on the far side";
            if (!results[i].hit) {
                if (++missed <= 3) ADD_FAILURE() << "case " << i << " missed at t " << expected;
                continue;
            }
            const double cosine = std::abs(glm::dot(glm::dvec3(n), glm::dvec3(rays[i].dir)));
            if (std::abs(results[i].t - expected) * cosine > 2e-7 && ++wrongT <= 3)
                ADD_FAILURE() << "case " << i << ": t " << results[i].t << ", expected "
                              << expected;
        }
        EXPECT_EQ(missed, 0u) << "of " << rays.size() << " rays starting " << gap << " away";
        EXPECT_EQ(wrongT, 0u);
    }
}

template <typename Runner>
void CheckContactShadowsAreDark(const Runner& run) {
    const vec3 n = kContactNormal;
    const vec3 u = Perpendicular(n), v = glm::cross(n, u);
    for (float gap : {1e-5f, 4e-6f}) {
        SCOPED_TRACE(std::string(Runner::kName) + " gap " + std::to_string(gap));
        RenderScene scene;
        scene.AddMaterial({});
        scene.AddInstance(AddMeshBlas(scene, Square(kContactCentre, n, 1.0f)), 0, glm::mat4(1.0f));
        scene.AddInstance(AddMeshBlas(scene, Square(kContactCentre + gap * n, n, 0.75f)), 0,
                          glm::mat4(1.0f));
        scene.BuildTlas();
        // Primary rays start inside the gap and look down at the receiver under the occluder;
        // their shadow rays go toward 16 x 16 lights over the hemisphere.
        std::vector<SpawnCase> cases;
        for (int p = 0; p < 16; ++p) {
            const vec3 at =
                kContactCentre + 0.1f * float(p % 4 - 1.5f) * u + 0.1f * float(p / 4 - 1.5f) * v;
            const vec3 down = -Hemisphere(n, 1.2f, 0.7f * float(p));
            for (int e = 0; e < 16; ++e)
                for (int a = 0; a < 16; ++a) {
                    const float elevation = 0.01745f * (1.0f + 88.0f * float(e) / 15.0f);
                    const vec3 light = Hemisphere(n, elevation, 0.3927f * float(a) + 0.1f);
                    cases.push_back(
                        {{at + 0.5f * gap * n, kInfinity, down, 0.0f}, light, SpawnMode::kGiven});
                }
        }
        const std::vector<SpawnResult> results = run.Spawn(scene, cases);
        uint32_t missedPrimary = 0, lit = 0;
        for (size_t i = 0; i < results.size(); ++i) {
            const SpawnResult& r = results[i];
            if (!r.primaryHit || r.primaryInstance != 0) {
                ++missedPrimary;
                continue;
            }
            if ((!r.occluded || r.spawnedInstance != 1) && ++lit <= 3)
                ADD_FAILURE() << "case " << i << " (light " << i % 256 << ") is lit";
        }
        EXPECT_EQ(missedPrimary, 0u) << "primary rays from inside the gap find the receiver";
        EXPECT_EQ(lit, 0u) << "of " << results.size() << " shadow rays under the occluder";
    }
}

// Ray/box in double: entry distance if the ray meets [lo, hi] at t > 0.
inline std::optional<double> HitBoxDouble(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo,
                                          glm::dvec3 hi) {
    double t0 = 0, t1 = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return std::nullopt;
            continue;
        }
        double nearT = (lo[a] - o[a]) / d[a], farT = (hi[a] - o[a]) / d[a];
        if (nearT > farT) std::swap(nearT, farT);
        t0 = std::max(t0, nearT);
        t1 = std::min(t1, farT);
    }
    if (t0 > t1) return std::nullopt;
    return t0;
}

// radius 0: the ground is a plane (a 400 x 400 square at y = 0).
template <typename Runner>
void CheckSmallBoxShadowOnGround(const Runner& run, float radius) {
    SCOPED_TRACE(std::string(Runner::kName) + " ground radius " + std::to_string(radius));
    const float size = 0.05f;
    RenderScene scene;
    scene.AddMaterial({});
    if (radius > 0.0f) {
        const Sphere ground{vec3(0), radius};
        scene.AddInstance(AddSphereBlas(scene, std::span(&ground, 1)), 0,
                          Placement(vec3(0, -radius, 0)));
    } else {
        scene.AddInstance(AddMeshBlas(scene, Square(vec3(0), vec3(0, 1, 0), 200.0f)), 0,
                          glm::mat4(1.0f));
    }
    const vec3 lo(-0.5f * size, 0.0f, -0.5f * size), hi(0.5f * size, size, 0.5f * size);
    TriangleMesh box;
    for (int corner = 0; corner < 8; ++corner)
        box.positions.push_back(
            vec3(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z));
    box.indices = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    scene.AddInstance(AddMeshBlas(scene, box), 0, glm::mat4(1.0f));
    scene.BuildTlas();
    const vec3 light = glm::normalize(vec3(std::cos(0.44f), std::sin(0.44f), 0.3f));
    // Seen from 3 box sizes up and back, toward the shadow; a 64 x 64 grid of ground points.
    const vec3 eye = vec3(-3.0f, 2.5f, 2.0f) * size;
    std::vector<SpawnCase> cases;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 64; ++j) {
            const vec3 target =
                size * vec3(-3.0f + 4.0f * float(i) / 63.0f, 0.0f, -2.5f + 3.5f * float(j) / 63.0f);
            cases.push_back({{eye, kInfinity, target - eye, 0.0f}, light, SpawnMode::kGiven});
        }
    const std::vector<SpawnResult> results = run.Spawn(scene, cases);
    const glm::dvec3 centre(0, -double(radius), 0), margin(1e-4), blo(lo), bhi(hi);
    uint32_t checked = 0, shadowed = 0, wrong = 0, selfShadowed = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        const glm::dvec3 o(cases[i].primary.origin), d(cases[i].primary.dir);
        double tGround;
        if (radius > 0.0f) {  // the near root, stably
            const glm::dvec3 f = o - centre;
            const double a = glm::dot(d, d), b = glm::dot(f, d);
            const double c = glm::dot(f, f) - double(radius) * radius;
            const double disc = b * b - a * c;
            if (disc < 0) continue;
            tGround = c / (-b + std::sqrt(disc));
        } else {
            tGround = -o.y / d.y;
        }
        if (HitBoxDouble(o, d, blo - margin, bhi + margin).value_or(1e300) < tGround) continue;
        const glm::dvec3 p = o + tGround * d;
        const bool big = HitBoxDouble(p, glm::dvec3(light), blo - margin, bhi + margin).has_value();
        const bool small =
            HitBoxDouble(p, glm::dvec3(light), blo + margin, bhi - margin).has_value();
        if (big != small) continue;
        const SpawnResult& r = results[i];
        ASSERT_TRUE(r.primaryHit && r.primaryInstance == 0) << "case " << i;
        ++checked;
        shadowed += big;
        if (r.occluded && r.spawnedHit && r.spawnedInstance == 0) ++selfShadowed;
        if (bool(r.occluded) != big && ++wrong <= 3)
            ADD_FAILURE() << "case " << i << (big ? " lit" : " shadowed") << ", point " << p.x
                          << " " << p.y << " " << p.z;
    }
    EXPECT_GT(checked, cases.size() / 2);
    EXPECT_GT(shadowed, 200u);
    EXPECT_EQ(wrong, 0u) << "of " << checked << " ground points";
    EXPECT_EQ(selfShadowed, 0u) << "ground points shadowed by the ground itself";
}

template <typename Runner>
void CheckSmallBoxShadowsOnGrounds(const Runner& run) {
    for (float radius : {0.0f, 1e5f, 1e6f}) CheckSmallBoxShadowOnGround(run, radius);
}

}  // namespace rtrt::robust
