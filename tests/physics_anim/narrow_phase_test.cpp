// Contact generation: normals, separations and points for each shape pair in simple poses.
#include "engine/physics_anim/narrow_phase.h"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

namespace rtrt::physics {
namespace {

constexpr float kTolerance = 1e-5f;
const float kSqrt2 = std::sqrt(2.0f);

void ExpectNear(vec3 actual, vec3 expected, float tolerance = kTolerance) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

OrientedBox Box(vec3 centre, vec3 halfExtents, glm::quat rotation = glm::identity<glm::quat>()) {
    return {centre, glm::mat3_cast(rotation), halfExtents};
}

TEST(NarrowPhaseTest, SpheresApartWithinAndBeyondTheMargin) {
    Manifold m;
    EXPECT_FALSE(CollideSpheres(vec3(0.0f), 1.0f, vec3(3.0f, 0.0f, 0.0f), 1.0f, 0.5f, m));
    ASSERT_TRUE(CollideSpheres(vec3(0.0f), 1.0f, vec3(3.0f, 0.0f, 0.0f), 1.0f, 2.0f, m));
    ASSERT_EQ(m.count, 1);
    ExpectNear(m.normal, vec3(1.0f, 0.0f, 0.0f));
    EXPECT_FLOAT_EQ(m.points[0].separation, 1.0f);
    ExpectNear(m.points[0].point, vec3(1.5f, 0.0f, 0.0f));
}

TEST(NarrowPhaseTest, OverlappingSpheres) {
    Manifold m;
    ASSERT_TRUE(CollideSpheres(vec3(0.0f), 1.0f, vec3(0.0f, 1.5f, 0.0f), 1.0f, 0.0f, m));
    ExpectNear(m.normal, vec3(0.0f, 1.0f, 0.0f));
    EXPECT_FLOAT_EQ(m.points[0].separation, -0.5f);
    ExpectNear(m.points[0].point, vec3(0.0f, 0.75f, 0.0f));
}

TEST(NarrowPhaseTest, SphereSinkingIntoPlane) {
    Manifold m;
    const PlaneShape floor{vec3(0.0f, 1.0f, 0.0f), 0.0f};
    ASSERT_TRUE(CollidePlaneSphere(floor, vec3(2.0f, 0.8f, 0.0f), 1.0f, 0.0f, m));
    ExpectNear(m.normal, vec3(0.0f, 1.0f, 0.0f));
    EXPECT_NEAR(m.points[0].separation, -0.2f, kTolerance);
    ExpectNear(m.points[0].point, vec3(2.0f, -0.1f, 0.0f));
    EXPECT_FALSE(CollidePlaneSphere(floor, vec3(0.0f, 1.2f, 0.0f), 1.0f, 0.1f, m));
}

TEST(NarrowPhaseTest, SphereAboveABoxFace) {
    Manifold m;
    ASSERT_TRUE(
        CollideBoxSphere(Box(vec3(0.0f), vec3(1.0f)), vec3(0.5f, 3.0f, 0.0f), 1.0f, 2.0f, m));
    ExpectNear(m.normal, vec3(0.0f, 1.0f, 0.0f));
    EXPECT_FLOAT_EQ(m.points[0].separation, 1.0f);
    ExpectNear(m.points[0].point, vec3(0.5f, 1.5f, 0.0f));
}

TEST(NarrowPhaseTest, SphereCentreInsideABoxLeavesByTheNearestFace) {
    Manifold m;
    ASSERT_TRUE(CollideBoxSphere(Box(vec3(0.0f), vec3(1.0f, 1.0f, 2.0f)), vec3(0.2f, -0.6f, 0.0f),
                                 0.25f, 0.0f, m));
    ExpectNear(m.normal, vec3(0.0f, -1.0f, 0.0f));
    EXPECT_NEAR(m.points[0].separation, -0.65f, kTolerance);
}

TEST(NarrowPhaseTest, SphereBesideTheEdgeOfARotatedBox) {
    Manifold m;
    const OrientedBox box =
        Box(vec3(0.0f), vec3(1.0f), glm::angleAxis(0.25f * kPi, vec3(0.0f, 0.0f, 1.0f)));
    ASSERT_TRUE(CollideBoxSphere(box, vec3(kSqrt2 + 1.5f, 0.0f, 0.3f), 1.0f, 1.0f, m));
    ExpectNear(m.normal, vec3(1.0f, 0.0f, 0.0f));
    EXPECT_NEAR(m.points[0].separation, 0.5f, kTolerance);
}

TEST(NarrowPhaseTest, BoxRestingOnPlaneTouchesAtFourCorners) {
    Manifold m;
    const PlaneShape floor{vec3(0.0f, 1.0f, 0.0f), 0.0f};
    ASSERT_TRUE(
        CollidePlaneBox(floor, Box(vec3(0.0f, 0.5f, 0.0f), vec3(1.0f, 0.5f, 2.0f)), 0.01f, m));
    ASSERT_EQ(m.count, 4);
    for (int i = 0; i < m.count; ++i) {
        EXPECT_EQ(m.points[i].separation, 0.0f);
        EXPECT_EQ(m.points[i].point.y, 0.0f);
        EXPECT_EQ(std::fabs(m.points[i].point.x), 1.0f);
        EXPECT_EQ(std::fabs(m.points[i].point.z), 2.0f);
    }
}

TEST(NarrowPhaseTest, BoxOnItsEdgeTouchesThePlaneAtTwoCorners) {
    Manifold m;
    const PlaneShape floor{vec3(0.0f, 1.0f, 0.0f), 0.0f};
    const OrientedBox box = Box(vec3(0.0f, kSqrt2, 0.0f), vec3(1.0f),
                                glm::angleAxis(0.25f * kPi, vec3(0.0f, 0.0f, 1.0f)));
    ASSERT_TRUE(CollidePlaneBox(floor, box, 0.01f, m));
    ASSERT_EQ(m.count, 2);
    for (int i = 0; i < m.count; ++i) EXPECT_NEAR(m.points[i].separation, 0.0f, kTolerance);
}

TEST(NarrowPhaseTest, StackedBoxesTouchOverTheFaceOverlap) {
    Manifold m;
    const OrientedBox bottom = Box(vec3(0.0f), vec3(1.0f));
    const OrientedBox top = Box(vec3(0.5f, 1.9f, 0.0f), vec3(1.0f));
    ASSERT_TRUE(CollideBoxes(bottom, top, 0.0f, m));
    ExpectNear(m.normal, vec3(0.0f, 1.0f, 0.0f));
    ASSERT_EQ(m.count, 4);
    for (int i = 0; i < m.count; ++i) {
        EXPECT_NEAR(m.points[i].separation, -0.1f, kTolerance);
        EXPECT_NEAR(m.points[i].point.y, 0.95f, kTolerance);
        // The overlap of the faces is x in [-0.5, 1], z in [-1, 1].
        EXPECT_TRUE(std::fabs(m.points[i].point.x + 0.5f) < kTolerance ||
                    std::fabs(m.points[i].point.x - 1.0f) < kTolerance);
        EXPECT_NEAR(std::fabs(m.points[i].point.z), 1.0f, kTolerance);
    }
    // The same pair the other way round has the opposite normal.
    ASSERT_TRUE(CollideBoxes(top, bottom, 0.0f, m));
    ExpectNear(m.normal, vec3(0.0f, -1.0f, 0.0f));
}

TEST(NarrowPhaseTest, TwistedBoxOnABoxTouchesAtTheOctagonOfTheirFaces) {
    Manifold m;
    const OrientedBox bottom = Box(vec3(0.0f), vec3(1.0f));
    const OrientedBox top = Box(vec3(0.0f, 2.0f, 0.0f), vec3(1.0f),
                                glm::angleAxis(0.25f * kPi, vec3(0.0f, 1.0f, 0.0f)));
    ASSERT_TRUE(CollideBoxes(bottom, top, 0.01f, m));
    EXPECT_EQ(m.count, 8);
    for (int i = 0; i < m.count; ++i) EXPECT_NEAR(m.points[i].separation, 0.0f, kTolerance);
}

TEST(NarrowPhaseTest, CrossedEdgesMakeOneEdgeContact) {
    Manifold m;
    constexpr float kGap = 0.05f;
    const OrientedBox a =
        Box(vec3(0.0f), vec3(1.0f), glm::angleAxis(0.25f * kPi, vec3(1.0f, 0.0f, 0.0f)));
    const OrientedBox b = Box(vec3(0.0f, 2.0f * kSqrt2 + kGap, 0.0f), vec3(1.0f),
                              glm::angleAxis(0.25f * kPi, vec3(0.0f, 0.0f, 1.0f)));
    ASSERT_TRUE(CollideBoxes(a, b, 0.1f, m));
    ASSERT_EQ(m.count, 1);
    ExpectNear(m.normal, vec3(0.0f, 1.0f, 0.0f));
    EXPECT_NEAR(m.points[0].separation, kGap, kTolerance);
    ExpectNear(m.points[0].point, vec3(0.0f, kSqrt2 + 0.5f * kGap, 0.0f));
    EXPECT_FALSE(CollideBoxes(a, b, 0.01f, m));
}

}  // namespace
}  // namespace rtrt::physics
