#pragma once
// The slab test's hard cases (engine/geometry/slab_test.h), each with its expected answer: zero and
// negative-zero direction components, rays lying in a box face, flat and point-like boxes, NaN
// lanes, tMax exactly at the entry. The expected value follows from the definition of an inclusive
// test: a ray hits the closed box [min, max] if some t in [0, tMax] puts o + t d in it.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "tests/robust/cases.h"

namespace rtrt::robust {

struct NamedSlabCase {
    const char* why;
    SlabCase c;
    bool expected;
};

inline std::vector<NamedSlabCase> SlabCases() {
    const float inf = kInfinity, nz = -0.0f;
    const vec3 lo(-1), hi(1);
    auto ray = [](vec3 o, vec3 d, float tMax = kInfinity) { return Ray{o, tMax, d, 0}; };
    std::vector<NamedSlabCase> cases = {
        {"axis ray, +0 components, through the box", {lo, hi, ray({0, 0, -5}, {0, 0, 1})}, true},
        {"axis ray, +0 components, beside the box", {lo, hi, ray({2, 0, -5}, {0, 0, 1})}, false},
        {"axis ray, -0 components, through", {lo, hi, ray({0, 0, -5}, {nz, nz, 1})}, true},
        {"axis ray, -0 components, beside", {lo, hi, ray({0, 1.5f, -5}, {nz, nz, 1})}, false},
        {"negative axis ray from behind", {lo, hi, ray({0, 0, 5}, {nz, 0, -1})}, true},
        {"box behind the origin", {lo, hi, ray({0, 0, 5}, {0, 0, 1})}, false},
        {"origin inside", {lo, hi, ray({0, 0, 0}, {0, 0, 1})}, true},
        {"origin inside, -0 components", {lo, hi, ray({0, 0, 0}, {nz, nz, -1})}, true},
        {"tMax short of the entry (t = 4)", {lo, hi, ray({0, 0, -5}, {0, 0, 1}, 3.9f)}, false},
        {"tMax exactly at the entry", {lo, hi, ray({0, 0, -5}, {0, 0, 1}, 4.0f)}, true},
        {"tMax 0, origin on the near face", {lo, hi, ray({0, 0, -1}, {0, 0, 1}, 0.0f)}, true},
        // Rays in a face plane: (plane - o) = 0 times 1/d = +-inf is NaN, which must be dropped.
        {"in face x = 1, dx = +0", {lo, hi, ray({1, 0, -5}, {0, 0, 1})}, true},
        {"in face x = 1, dx = -0", {lo, hi, ray({1, 0, -5}, {nz, 0, 1})}, true},
        {"in face x = -1, dx = +0", {lo, hi, ray({-1, 0, -5}, {0, 0, 1})}, true},
        {"in face x = -1, dx = -0", {lo, hi, ray({-1, 0, -5}, {nz, 0, 1})}, true},
        {"along edge x = 1, y = 1", {lo, hi, ray({1, 1, -5}, {0, nz, 1})}, true},
        {"along edge x = -1, y = -1, -0", {lo, hi, ray({-1, -1, 5}, {nz, nz, -1})}, true},
        {"just outside face x = 1", {lo, hi, ray({1.0000001f, 0, -5}, {0, 0, 1})}, false},
        {"in face plane, diagonal in it", {lo, hi, ray({1, -3, -3}, {0, 1, 1})}, true},
        {"in face plane, passing beside", {lo, hi, ray({1, -3, 0}, {0, 1, 1})}, false},
        {"through a corner exactly", {lo, hi, ray({-2, -2, -2}, {1, 1, 1})}, true},
        {"grazing a corner from outside", {lo, hi, ray({-3, 1, 1}, {1, 0, 0})}, true},
        // Flat boxes (zero extent in one axis): planar geometry and axis-aligned instances.
        {"flat y box, ray down", {{-1, 0, -1}, {1, 0, 1}, ray({0.5f, 3, 0.2f}, {0, -1, 0})}, true},
        {"flat y box, ray up, away",
         {{-1, 0, -1}, {1, 0, 1}, ray({0.5f, 3, 0.2f}, {0, 1, 0})},
         false},
        {"flat y box, ray in its plane",
         {{-1, 0, -1}, {1, 0, 1}, ray({-3, 0, 0}, {1, 0, 0})},
         true},
        {"flat y box, in plane, -0", {{-1, 0, -1}, {1, 0, 1}, ray({-3, 0, 0}, {1, nz, nz})}, true},
        {"flat y box, slanted ray", {{-1, 0, -1}, {1, 0, 1}, ray({-2, 1, 0}, {1, -1, 0.1f})}, true},
        {"flat x box, slanted miss", {{0, -1, -1}, {0, 1, 1}, ray({-1, 3, 0}, {1, 1, 0})}, false},
        {"point box, ray through it", {{1, 2, 3}, {1, 2, 3}, ray({1, 2, -5}, {0, 0, 1})}, true},
        {"point box, diagonal through", {{1, 2, 3}, {1, 2, 3}, ray({0, 1, 2}, {1, 1, 1})}, true},
        {"point box, beside", {{1, 2, 3}, {1, 2, 3}, ray({1, 2.0001f, -5}, {0, 0, 1})}, false},
        // Large values: no overflow to inf - inf.
        {"huge box, far origin", {vec3(-3e38f), vec3(3e38f), ray(vec3(-3.2e38f), {1, 1, 1})}, true},
        {"far box along a tiny direction",
         {vec3(1e30f), vec3(2e30f), ray(vec3(0), {1e-30f, 1e-30f, 1e-30f})},
         true},
        {"denormal direction component", {lo, hi, ray({0, 0, -5}, {1e-40f, 0, 1})}, true},
        // NaN and infinite rays are screened by IsTraceable before traversal; the slab test alone
        // must still not claim a hit through NaN arithmetic where the finite lanes rule it out.
        // (A NaN tMax breaks the test's precondition — its accumulators are never NaN — and the
        // back ends differ there: the GPU's fminf drops it. IsTraceable rejects such rays first;
        // CheckBadRays covers them on both back ends.)
        {"NaN direction lane, finite lanes miss",
         {lo, hi, ray({0, 5, -5}, {std::numeric_limits<float>::quiet_NaN(), 0, 1})},
         false},
        {"infinite tMax", {lo, hi, ray({0, 0, -5}, {0, 0, 1}, inf)}, true},
    };
    return cases;
}

template <typename Runner>
void CheckSlabCases(const Runner& run) {
    SCOPED_TRACE(Runner::kName);
    const std::vector<NamedSlabCase> named = SlabCases();
    std::vector<SlabCase> cases;
    for (const NamedSlabCase& n : named) cases.push_back(n.c);
    const std::vector<uint32_t> got = run.Slab(cases);
    for (size_t i = 0; i < named.size(); ++i)
        EXPECT_EQ(got[i] != 0, named[i].expected) << named[i].why;
}

}  // namespace rtrt::robust
