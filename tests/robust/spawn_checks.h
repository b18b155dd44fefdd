#pragma once
// Self-intersection: secondary rays spawned from surfaces far from the origin (1e3 to 1e5, in the
// BLAS's own coordinates or through an instance translation) and from huge spheres leave their
// surface (engine/render_rt/surface.h offsets the origin by the point's error bound, pbrt-v4
// section 6.8). Expected values:
// - a mirror ray or a ray toward a light on the outside of a plane or a convex object hits
//   nothing: the scene holds that object alone (0 self-hits, 0 occluded shadow rays);
// - a ray continuing into a closed box or sphere (a refracted ray) hits the same object on its far
//   side, at the chord length computed in double from the hit point, to within 16 ulps of the
//   coordinates' magnitude (their float spacing; a self-hit would be at t ~ 0).
#include <gtest/gtest.h>

#include <string>

#include "tests/robust/cases.h"
#include "tests/robust/closed_meshes.h"
#include "tests/robust/scene_builder.h"

namespace rtrt::robust {

// A 10 x 10 quad, two triangles, centred on `centre` in the plane with normal n.
inline TriangleMesh Quad(vec3 centre, vec3 n) {
    n = glm::normalize(n);
    const vec3 u = Perpendicular(n);
    const vec3 v = glm::cross(n, u);
    TriangleMesh m;
    for (vec3 c : {-u - v, u - v, u + v, -u + v}) m.positions.push_back(centre + 5.0f * c);
    m.indices = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

// Primary rays from 3 units off the surface point `at` (outside, along n) to a grid of 64
// points around `at` on the surface, each spawned in the given mode.
inline std::vector<SpawnCase> CasesAround(vec3 at, vec3 n, float spread, SpawnMode mode,
                                          vec3 given = vec3(0)) {
    n = glm::normalize(n);
    const vec3 u = Perpendicular(n);
    const vec3 v = glm::cross(n, u);
    const vec3 eye = at + 3.0f * n + 0.37f * u;
    std::vector<SpawnCase> cases;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
            const vec3 target =
                at + spread * ((float(i) - 3.5f) / 4.0f * u + (float(j) - 3.5f) / 4.0f * v);
            cases.push_back({{eye, kInfinity, target - eye, 0}, given, mode});
        }
    return cases;
}

// Spawns mirror rays and rays toward a light 40 degrees off the normal: none may hit anything.
template <typename Runner>
void ExpectLeavesSurface(const Runner& run, const RenderScene& scene, vec3 at, vec3 n, float spread,
                         const std::string& what) {
    SCOPED_TRACE(std::string(Runner::kName) + " " + what);
    n = glm::normalize(n);
    const vec3 side = Perpendicular(n);
    const vec3 light = std::cos(0.7f) * n + std::sin(0.7f) * side;
    std::vector<SpawnCase> cases = CasesAround(at, n, spread, SpawnMode::kReflect);
    for (const SpawnCase& c : CasesAround(at, n, spread, SpawnMode::kGiven, light))
        cases.push_back(c);
    const std::vector<SpawnResult> results = run.Spawn(scene, cases);
    uint32_t missedPrimary = 0, selfHits = 0;
    for (size_t i = 0; i < results.size(); ++i) {
        missedPrimary += !results[i].primaryHit;
        if (results[i].primaryHit && (results[i].spawnedHit || results[i].occluded) &&
            ++selfHits <= 3)
            ADD_FAILURE() << "case " << i << " re-hit its surface at t = " << results[i].spawnedT;
    }
    EXPECT_EQ(missedPrimary, 0u) << "the primary rays are aimed at the surface";
    EXPECT_EQ(selfHits, 0u) << "of " << results.size() << " spawned rays";
}

template <typename Runner>
void CheckSpawnFromFarPlanes(const Runner& run) {
    const vec3 n = glm::normalize(vec3(0.3f, 1.0f, -0.6f));
    for (float d : {1e3f, 1e4f, 1e5f}) {
        const vec3 at = d * glm::normalize(vec3(1, -0.5f, 0.8f));
        {  // far coordinates in the BLAS itself
            RenderScene scene;
            scene.AddMaterial({});
            scene.AddInstance(AddMeshBlas(scene, Quad(at, n)), 0, glm::mat4(1.0f));
            scene.BuildTlas();
            ExpectLeavesSurface(run, scene, at, n, 4.0f,
                                "plane with vertices at " + std::to_string(d));
        }
        {  // a quad at the origin moved there by its instance (rotated 30 degrees about x)
            RenderScene scene;
            scene.AddMaterial({});
            const glm::mat4 place = Placement(at, 0.5236f, vec3(1, 0, 0));
            scene.AddInstance(AddMeshBlas(scene, Quad(vec3(0), vec3(0, 1, 0))), 0, place);
            scene.BuildTlas();
            const vec3 worldN = glm::normalize(vec3(place * glm::vec4(0, 1, 0, 0)));
            ExpectLeavesSurface(run, scene, vec3(place[3]), worldN, 4.0f,
                                "instance translated by " + std::to_string(d));
        }
        {  // a unit sphere translated there
            RenderScene scene;
            scene.AddMaterial({});
            const Sphere s{vec3(0), 1.0f};
            scene.AddInstance(AddSphereBlas(scene, std::span(&s, 1)), 0, Placement(at));
            scene.BuildTlas();
            ExpectLeavesSurface(run, scene, at + n, n, 0.2f,
                                "sphere translated by " + std::to_string(d));
        }
    }
    for (float radius : {1e5f, 1e6f}) {  // huge ground spheres, top at y = 0
        RenderScene scene;
        scene.AddMaterial({});
        const Sphere s{vec3(0), radius};
        scene.AddInstance(AddSphereBlas(scene, std::span(&s, 1)), 0,
                          Placement(vec3(0, -radius, 0)));
        scene.BuildTlas();
        ExpectLeavesSurface(run, scene, vec3(0), vec3(0, 1, 0), 4.0f,
                            "ground sphere of radius " + std::to_string(radius));
    }
}

// Rays continuing into a closed object far from the origin find its far side, not its near side.
template <typename Runner>
void CheckSpawnIntoFarObjects(const Runner& run) {
    for (float d : {1e3f, 1e4f, 1e5f}) {
        const vec3 at = d * glm::normalize(vec3(-0.4f, 0.9f, 0.5f));
        const float ulp16 = 16.0f * d * 0x1p-23f;
        for (int shape = 0; shape < 2; ++shape) {
            SCOPED_TRACE(std::string(Runner::kName) + (shape ? " sphere at " : " box at ") +
                         std::to_string(d));
            RenderScene scene;
            scene.AddMaterial({});
            const Sphere s{vec3(0), 1.0f};
            const uint32_t blas =
                shape ? AddSphereBlas(scene, std::span(&s, 1))
                      : AddMeshBlas(scene, SubdividedBox(3, vec3(-1), vec3(1)).mesh);
            const glm::mat4 place = Placement(at, 0.3f, vec3(1, 2, 3));
            scene.AddInstance(blas, 0, place);
            scene.BuildTlas();
            // Straight through from a point 4 units away, aimed at points near the centre.
            std::vector<SpawnCase> cases;
            for (int i = 0; i < 64; ++i) {
                const vec3 eye = at + vec3(4.0f, 0.5f * std::sin(float(i)), 0.3f);
                const vec3 target =
                    at + 0.4f * vec3(std::sin(1.7f * i), std::cos(2.3f * i), std::sin(0.9f * i));
                cases.push_back(
                    {{eye, kInfinity, target - eye, 0}, target - eye, SpawnMode::kGiven});
            }
            const std::vector<SpawnResult> results = run.Spawn(scene, cases);
            const glm::dmat4 toObject = glm::inverse(glm::dmat4(place));
            for (size_t i = 0; i < cases.size(); ++i) {
                const SpawnResult& r = results[i];
                ASSERT_TRUE(r.primaryHit) << "case " << i;
                ASSERT_TRUE(r.spawnedHit) << "case " << i << ": the continued ray left the object";
                // Chord from the hit point along the unit direction, in double, object space.
                const glm::dvec3 p = glm::dvec3(toObject * glm::dvec4(glm::dvec3(r.point), 1.0));
                const glm::dvec3 dir = glm::normalize(
                    glm::dvec3(toObject * glm::dvec4(glm::dvec3(cases[i].dir), 0.0)));
                double chord;
                if (shape) {
                    chord = -2.0 * glm::dot(p, dir);  // |p| = 1: the far root of |p + t dir| = 1
                } else {
                    chord = 1e30;
                    for (int a = 0; a < 3; ++a)
                        if (dir[a] != 0)
                            chord = std::min(chord, ((dir[a] > 0 ? 1.0 : -1.0) - p[a]) / dir[a]);
                }
                EXPECT_NEAR(r.spawnedT, chord, ulp16) << "case " << i;
            }
        }
    }
}

}  // namespace rtrt::robust
