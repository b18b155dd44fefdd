// Packed normals (engine/geometry/packed_normal.h): the axes and the octahedron's edges decode
// exactly, every direction within the stated angle, and what cannot be a direction packs as +z.
#include "engine/geometry/packed_normal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rtrt {
namespace {

double AngleBetween(vec3 a, vec3 b) {
    const glm::dvec3 x = glm::normalize(glm::dvec3(a)), y = glm::normalize(glm::dvec3(b));
    return std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y));
}

TEST(PackedNormal, AxesDecodeExactly) {
    for (const vec3 axis : {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0),
                            vec3(0, 0, 1), vec3(0, 0, -1)})
        EXPECT_EQ(UnpackNormal(PackNormal(axis)), axis);
    EXPECT_EQ(UnpackNormal(PackNormal(vec3(0, 0, 5))), vec3(0, 0, 1));  // length does not matter
}

TEST(PackedNormal, EveryDirectionWithinAFewHundredthsOfAMilliradian) {
    std::mt19937 rng(7);
    std::normal_distribution<float> gauss;
    double worst = 0.0, worstRounded = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const vec3 n(gauss(rng), gauss(rng), gauss(rng));
        if (glm::length(n) < 1e-3f) continue;
        const vec3 decoded = UnpackNormal(PackNormal(n));
        EXPECT_NEAR(glm::length(decoded), 1.0f, 1e-6f);
        worst = std::max(worst, AngleBetween(n, decoded));
        worstRounded = std::max(worstRounded, AngleBetween(n, UnpackNormal(PackNormalRounded(n))));
    }
    EXPECT_LT(worst, 5e-5);
    EXPECT_LT(worstRounded, 1e-4);
    EXPECT_GT(worstRounded, worst);  // the precise encoder does better than rounding
    // The folded (z < 0) half near its seams, where the mapping is least even.
    for (const vec3 n :
         {vec3(0.7f, 0.7f, -0.01f), vec3(-0.5f, 1e-4f, -0.8f), vec3(1e-6f, -1, -1e-6f)})
        EXPECT_LT(AngleBetween(n, UnpackNormal(PackNormal(n))), 5e-5) << n.x << "," << n.y;
}

TEST(PackedNormal, WhatIsNoDirectionPacksAsUp) {
    for (const vec3 n : {vec3(0.0f), vec3(NAN, 0, 1), vec3(INFINITY, 0, 0)}) {
        EXPECT_EQ(UnpackNormal(PackNormal(n)), vec3(0, 0, 1));
        EXPECT_EQ(UnpackNormal(PackNormalRounded(n)), vec3(0, 0, 1));
    }
    // Every bit pattern decodes to a unit vector (files need no normal check).
    for (uint32_t bits : {0u, 0x80008000u, 0x7fff7fffu, 0xffffffffu, 0x80007fffu, 0x12345678u})
        EXPECT_NEAR(glm::length(UnpackNormal(bits)), 1.0f, 1e-6f) << bits;
}

}  // namespace
}  // namespace rtrt
