#pragma once
// Ray/triangle cases at the primitive level (engine/geometry/triangle_intersect.h):
// - direction-length invariance: object-space directions are not unit length (instance scale
//   divides them), so the same geometric ray with its direction scaled by 1e-30 .. 1e30 must hit
//   the same triangle at t scaled by the inverse; expected t |d| equal to the unit ray's to 1e-6;
// - tMax idempotence: testing again with tMax set to the t just found gives the same hit, bit for
//   bit (IntersectTriangle's contract: hits with t <= tMax), so the closest of several hits at
//   nearly equal t does not depend on the order they are tested in.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "tests/robust/cases.h"

namespace rtrt::robust {

template <typename Runner>
void CheckTriangleDirectionScale(const Runner& run) {
    SCOPED_TRACE(Runner::kName);
    const Triangle tri{vec3(-1, -1, 0.2f), vec3(1.3f, -0.7f, -0.1f), vec3(0.1f, 1.1f, 0.05f)};
    const float scales[] = {1e-30f, 1e-20f, 1e-10f, 1e-5f, 1.0f, 1e5f, 1e10f, 1e20f, 1e30f};
    std::vector<TriangleCase> cases;
    for (vec3 d : {vec3(0.1f, 0.05f, -1), vec3(-0.3f, 0.2f, -0.7f), vec3(0.02f, -0.9f, -0.4f)})
        for (float s : scales)
            cases.push_back({tri, {vec3(0.05f, 0.1f, 0) - 3.0f * d, kInfinity, s * d, 0}});
    const std::vector<PrimResult> got = run.Triangle(cases);
    for (size_t i = 0; i < cases.size(); ++i) {
        const PrimResult& unit = got[i - i % 9 + 4];  // scale 1 of the same direction
        ASSERT_TRUE(got[i].hit) << "scale " << scales[i % 9];
        const float lengthT = got[i].t * glm::length(glm::dvec3(cases[i].ray.dir));
        const float unitT = unit.t * glm::length(glm::dvec3(cases[i - i % 9 + 4].ray.dir));
        EXPECT_NEAR(lengthT, unitT, 1e-6f * unitT) << "scale " << scales[i % 9];
    }
}

template <typename Runner>
void CheckTriangleTMaxIdempotent(const Runner& run) {
    SCOPED_TRACE(Runner::kName);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<TriangleCase> cases;
    for (int i = 0; i < 200000; ++i) {
        const Triangle tri{vec3(u(rng), u(rng), u(rng)), vec3(u(rng), u(rng), u(rng)),
                           vec3(u(rng), u(rng), u(rng))};
        const vec3 target = (tri.v0 + tri.v1 + tri.v2) / 3.0f + 0.1f * vec3(u(rng), u(rng), u(rng));
        const vec3 origin = 4.0f * vec3(u(rng), u(rng), u(rng));
        cases.push_back(
            {tri, {origin, kInfinity, (0.5f + 2.0f * std::abs(u(rng))) * (target - origin), 0}});
    }
    const std::vector<PrimResult> first = run.Triangle(cases);
    std::vector<TriangleCase> again;
    for (size_t i = 0; i < cases.size(); ++i)
        if (first[i].hit) {
            again.push_back(cases[i]);
            again.back().ray.tMax = first[i].t;
        }
    ASSERT_GT(again.size(), cases.size() / 4);
    const std::vector<PrimResult> second = run.Triangle(again);
    uint32_t lost = 0;
    for (const PrimResult& r : second) lost += !r.hit;
    EXPECT_EQ(lost, 0u) << "of " << again.size() << " hits re-tested with tMax = their t";
}

}  // namespace rtrt::robust
