// Procedural motions and paths at known times.
#include "engine/physics_anim/procedural_motion.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

namespace rtrt::physics {
namespace {

constexpr float kTolerance = 1e-5f;

void ExpectNear(vec3 actual, vec3 expected, float tolerance = kTolerance) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

LocalTransform Apply(const ProceduralMotion& motion, double t, LocalTransform pose = {}) {
    ApplyMotion(motion, t, pose);
    return pose;
}

TEST(ProceduralMotionTest, SpinTurnsAtItsAngularSpeed) {
    const Spin spin{vec3(0.0f, 2.0f, 0.0f), 0.5f * kPi};  // a quarter turn per second
    const LocalTransform pose = Apply(spin, 1.0);
    // Counter-clockwise seen from +Y: +X goes to -Z.
    ExpectNear(pose.rotation * vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 0.0f, -1.0f));
    ExpectNear(Apply(spin, 4.0).rotation * vec3(1.0f, 0.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f));
}

TEST(ProceduralMotionTest, SpinComposesWithTheBaseRotation) {
    LocalTransform base;
    base.rotation = glm::angleAxis(0.5f * kPi, vec3(0.0f, 0.0f, 1.0f));  // +X to +Y
    const LocalTransform pose = Apply(Spin{vec3(0.0f, 1.0f, 0.0f), kPi}, 0.5, base);
    // First the base turns +X to +Y, then the spin about +Y leaves it there.
    ExpectNear(pose.rotation * vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f));
    ExpectNear(pose.rotation * vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 0.0f));
}

TEST(ProceduralMotionTest, OrbitAtQuarterPeriods) {
    const Orbit orbit{vec3(1.0f, 2.0f, 3.0f), 2.0f, vec3(0.0f, 1.0f, 0.0f), 4.0f};
    ExpectNear(Apply(orbit, 0.0).translation, vec3(3.0f, 2.0f, 3.0f));  // centre + radius * X
    ExpectNear(Apply(orbit, 1.0).translation, vec3(1.0f, 2.0f, 1.0f));  // a quarter: -Z
    ExpectNear(Apply(orbit, 2.0).translation, vec3(-1.0f, 2.0f, 3.0f));
    ExpectNear(Apply(orbit, 3.0).translation, vec3(1.0f, 2.0f, 5.0f));
    ExpectNear(Apply(orbit, 4.0 * 1000 + 1.0).translation, vec3(1.0f, 2.0f, 1.0f), 1e-4f);
}

TEST(ProceduralMotionTest, OrbitAboutAnyAxisStaysInItsPlaneAtItsRadius) {
    const vec3 axis = glm::normalize(vec3(1.0f, 2.0f, -3.0f));
    const Orbit orbit{vec3(0.0f), 1.5f, axis, 3.0f};
    for (double t = 0.0; t < 3.0; t += 0.37) {
        const vec3 p = Apply(orbit, t).translation;
        EXPECT_NEAR(glm::length(p), 1.5f, kTolerance);
        EXPECT_NEAR(glm::dot(p, axis), 0.0f, kTolerance);
    }
}

TEST(ProceduralMotionTest, BobAddsASineAlongItsAxis) {
    const Bob bob{0.5f, 2.0f, vec3(0.0f, 1.0f, 0.0f)};
    LocalTransform base;
    base.translation = vec3(1.0f, 1.0f, 1.0f);
    ExpectNear(Apply(bob, 0.0, base).translation, vec3(1.0f, 1.0f, 1.0f));
    ExpectNear(Apply(bob, 0.125, base).translation, vec3(1.0f, 1.5f, 1.0f));  // a quarter cycle
    ExpectNear(Apply(bob, 0.375, base).translation, vec3(1.0f, 0.5f, 1.0f));
    ExpectNear(Apply(bob, 0.5, base).translation, vec3(1.0f, 1.0f, 1.0f));
}

TEST(ProceduralMotionTest, FollowPolylineAtSpeed) {
    auto path = std::make_shared<const Path>(
        std::vector<vec3>{vec3(0.0f), vec3(2.0f, 0.0f, 0.0f), vec3(2.0f, 0.0f, 2.0f),
                          vec3(0.0f, 0.0f, 2.0f)},
        PathKind::kPolyline, true);
    EXPECT_FLOAT_EQ(path->Length(), 8.0f);
    const FollowPath follow{path, 2.0f};
    ExpectNear(Apply(follow, 0.5).translation, vec3(1.0f, 0.0f, 0.0f));
    ExpectNear(Apply(follow, 1.5).translation, vec3(2.0f, 0.0f, 1.0f));
    ExpectNear(Apply(follow, 3.5).translation, vec3(0.0f, 0.0f, 1.0f));  // on the closing side
    ExpectNear(Apply(follow, 4.0 + 0.5).translation, vec3(1.0f, 0.0f, 0.0f));  // looped
}

TEST(ProceduralMotionTest, OpenPathStopsAtItsEnd) {
    const Path path({vec3(0.0f), vec3(0.0f, 3.0f, 0.0f)}, PathKind::kPolyline, false);
    ExpectNear(path.PointAt(1.0f), vec3(0.0f, 1.0f, 0.0f));
    ExpectNear(path.PointAt(10.0f), vec3(0.0f, 3.0f, 0.0f));
    ExpectNear(path.PointAt(-1.0f), vec3(0.0f));
}

TEST(ProceduralMotionTest, CatmullRomPassesThroughItsPointsAtEvenSpeed) {
    const std::vector<vec3> points{vec3(0.0f), vec3(2.0f, 0.0f, 0.0f), vec3(2.0f, 0.0f, 2.0f),
                                   vec3(0.0f, 0.0f, 2.0f)};
    const Path path(points, PathKind::kCatmullRom, true);
    for (size_t i = 0; i < points.size(); ++i)
        ExpectNear(path.PointAt(path.KnotDistance(i)), points[i]);
    ExpectNear(path.PointAt(path.Length()), points[0]);
    // By symmetry, half way between the first two knots is the segment's midpoint, which the
    // uniform spline bulges out to (1, 0, -0.25).
    ExpectNear(path.PointAt(0.5f * path.KnotDistance(1)), vec3(1.0f, 0.0f, -0.25f), 1e-4f);
    // Arc-length parameterised: equal distances give nearly equal chords.
    const float step = path.Length() / 64.0f;
    for (int i = 0; i < 64; ++i) {
        const float chord = glm::length(path.PointAt((i + 1) * step) - path.PointAt(i * step));
        EXPECT_NEAR(chord, step, 0.01f * step);
    }
}

TEST(ProceduralMotionTest, PathNeedsTwoFinitePoints) {
    EXPECT_THROW(Path({vec3(0.0f)}, PathKind::kPolyline, false), std::invalid_argument);
    EXPECT_THROW(Path({vec3(0.0f), vec3(kInfinity)}, PathKind::kCatmullRom, false),
                 std::invalid_argument);
}

TEST(ProceduralMotionTest, OrthonormalBasisIsRightHanded) {
    for (const vec3 n : {vec3(0, 1, 0), vec3(0, 0, -1), glm::normalize(vec3(1, -2, 0.5f))}) {
        vec3 u;
        vec3 v;
        OrthonormalBasis(n, u, v);
        ExpectNear(glm::cross(u, v), n);
        EXPECT_NEAR(glm::dot(u, n), 0.0f, kTolerance);
        EXPECT_NEAR(glm::length(u), 1.0f, kTolerance);
    }
}

}  // namespace
}  // namespace rtrt::physics
