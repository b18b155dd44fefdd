// Snell's law and the exact Fresnel equations at known angles.
#include "engine/render_rt/optics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rtrt {
namespace {

TEST(Optics, FresnelAtNormalIncidenceIsTheSquaredRatio) {
    // ((n - 1) / (n + 1))^2 = 0.04 for n = 1.5, from either side.
    EXPECT_NEAR(FresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);
    EXPECT_NEAR(FresnelDielectric(-1.0f, 1.5f), 0.04f, 1e-6f);
}

TEST(Optics, FresnelAtBrewsterAngleIsHalfThePerpendicularTerm) {
    // At Brewster's angle tan(theta) = n the parallel term vanishes; for n = 1.5 the
    // perpendicular reflectance is ((cos i - n cos t) / (cos i + n cos t))^2 = 0.1479.
    const float thetaB = std::atan(1.5f);
    EXPECT_NEAR(FresnelDielectric(std::cos(thetaB), 1.5f), 0.5f * 0.147929f, 1e-5f);
}

TEST(Optics, TotalInternalReflectionBeyondTheCriticalAngle) {
    // Inside glass (eta = 1/1.5) the critical angle is asin(1/1.5) = 41.81 degrees.
    const float critical = std::asin(1.0f / 1.5f);
    EXPECT_EQ(FresnelDielectric(std::cos(critical + 0.01f), 1.0f / 1.5f), 1.0f);
    EXPECT_LT(FresnelDielectric(std::cos(critical - 0.01f), 1.0f / 1.5f), 1.0f);
    vec3 wt;
    const float a = critical + 0.01f;
    EXPECT_FALSE(Refract(vec3(std::sin(a), std::cos(a), 0), vec3(0, 1, 0), 1.0f / 1.5f, &wt));
}

TEST(Optics, RefractionFollowsSnellsLaw) {
    const float thetaI = glm::radians(45.0f);
    vec3 wt;
    ASSERT_TRUE(Refract(vec3(std::sin(thetaI), std::cos(thetaI), 0), vec3(0, 1, 0), 1.5f, &wt));
    const float sinT = std::sin(thetaI) / 1.5f;  // Snell: sin(i) = 1.5 sin(t)
    EXPECT_NEAR(wt.x, -sinT, 1e-6f);
    EXPECT_NEAR(wt.y, -std::sqrt(1 - sinT * sinT), 1e-6f);
    EXPECT_NEAR(glm::length(wt), 1.0f, 1e-6f);
}

TEST(Optics, IndexOneIsInvisible) {
    EXPECT_NEAR(FresnelDielectric(0.3f, 1.0f), 0.0f, 1e-12f);
    vec3 wi = glm::normalize(vec3(0.3f, 0.8f, -0.1f)), wt;
    ASSERT_TRUE(Refract(wi, vec3(0, 1, 0), 1.0f, &wt));
    EXPECT_NEAR(glm::distance(wt, -wi), 0.0f, 1e-6f);
}

TEST(Optics, ReflectMirrorsAboutTheNormal) {
    EXPECT_EQ(Reflect(glm::normalize(vec3(1, 1, 0)), vec3(0, 1, 0)),
              glm::normalize(vec3(-1, 1, 0)));
}

}  // namespace
}  // namespace rtrt
