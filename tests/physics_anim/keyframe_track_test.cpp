// Keyframe tracks: exact values for step, linear, slerp and cubic-spline interpolation (glTF 2.0
// Appendix C evaluated by hand), morph weight tracks, clamping and looping.
#include "engine/physics_anim/keyframe_track.h"

#include <gtest/gtest.h>

#include "engine/physics_anim/quat_interp.h"

namespace rtrt::physics {
namespace {

const vec3 kUp(0.0f, 1.0f, 0.0f);

float AngleDegrees(const glm::quat& q) { return glm::degrees(glm::angle(q)); }

Vec3Track TwoKeys(Interpolation interpolation) {
    Vec3Track track;
    track.times = {1.0f, 3.0f};
    track.values = {vec3(0.0f, 0.0f, 0.0f), vec3(4.0f, -2.0f, 8.0f)};
    track.interpolation = interpolation;
    return track;
}

TEST(KeyframeTrackTest, StepHoldsTheEarlierKeyUntilTheNext) {
    const Vec3Track track = TwoKeys(Interpolation::kStep);
    EXPECT_EQ(SampleTrack(track, 1.0f), vec3(0.0f));
    EXPECT_EQ(SampleTrack(track, 2.999f), vec3(0.0f));
    EXPECT_EQ(SampleTrack(track, 3.0f), vec3(4.0f, -2.0f, 8.0f));
}

TEST(KeyframeTrackTest, LinearMidpointIsTheMeanOfTheKeys) {
    const Vec3Track track = TwoKeys(Interpolation::kLinear);
    EXPECT_EQ(SampleTrack(track, 2.0f), vec3(2.0f, -1.0f, 4.0f));
    EXPECT_EQ(SampleTrack(track, 1.5f), vec3(1.0f, -0.5f, 2.0f));
}

TEST(KeyframeTrackTest, OutsideItsKeysATrackHoldsItsEndValues) {
    const Vec3Track track = TwoKeys(Interpolation::kLinear);
    EXPECT_EQ(SampleTrack(track, 0.0f), vec3(0.0f));
    EXPECT_EQ(SampleTrack(track, 100.0f), vec3(4.0f, -2.0f, 8.0f));
}

TEST(KeyframeTrackTest, SlerpOfNinetyDegreesAtHalfTimeIsFortyFiveDegrees) {
    QuatTrack track;
    track.times = {0.0f, 1.0f};
    track.values = {glm::identity<glm::quat>(), glm::angleAxis(glm::radians(90.0f), kUp)};
    track.interpolation = Interpolation::kSlerp;
    const glm::quat half = SampleTrack(track, 0.5f);
    EXPECT_NEAR(AngleDegrees(half), 45.0f, 1e-4f);
    const vec3 axis = glm::axis(half);
    EXPECT_NEAR(axis.y, 1.0f, 1e-6f);
    // Constant angular speed: a quarter of the way is a quarter of the angle.
    EXPECT_NEAR(AngleDegrees(SampleTrack(track, 0.25f)), 22.5f, 1e-4f);
}

// Slerp keeps the angular speed constant; Nlerp agrees with it only at the midpoint.
TEST(KeyframeTrackTest, LinearRotationIsNlerpWhichDiffersFromSlerpOffTheMidpoint) {
    QuatTrack track;
    track.times = {0.0f, 1.0f};
    track.values = {glm::identity<glm::quat>(), glm::angleAxis(glm::radians(90.0f), kUp)};
    track.interpolation = Interpolation::kLinear;
    EXPECT_NEAR(AngleDegrees(SampleTrack(track, 0.5f)), 45.0f, 1e-4f);
    const float quarter = AngleDegrees(SampleTrack(track, 0.25f));
    // In half-angles the keys are (cos 0, sin 0) and (cos 45, sin 45); their blend at 0.25 points
    // at atan2(0.25 sin 45, 0.75 + 0.25 cos 45).
    const float half = std::atan2(0.25f * std::sin(glm::radians(45.0f)),
                                  0.75f + 0.25f * std::cos(glm::radians(45.0f)));
    EXPECT_NEAR(quarter, glm::degrees(2.0f * half), 1e-4f);
    EXPECT_GT(std::fabs(quarter - 22.5f), 0.1f);
}

TEST(KeyframeTrackTest, SlerpTakesTheShorterWay) {
    // 350 degrees about +Y is -10 degrees: halfway is -5 degrees, not 175.
    const glm::quat a = glm::identity<glm::quat>();
    const glm::quat b = glm::angleAxis(glm::radians(350.0f), kUp);
    const glm::quat half = Slerp(a, b, 0.5f);
    EXPECT_NEAR(AngleDegrees(half), 5.0f, 1e-3f);
    const vec3 x = half * vec3(1.0f, 0.0f, 0.0f);
    EXPECT_NEAR(x.z, std::sin(glm::radians(5.0f)), 1e-5f);  // turned clockwise seen from +Y
}

TEST(KeyframeTrackTest, ClampedClipHoldsItsEndPose) {
    KeyframeClip clip;
    clip.translation = TwoKeys(Interpolation::kLinear);
    clip.wrap = WrapMode::kClamp;
    EXPECT_EQ(clip.Duration(), 3.0f);
    LocalTransform pose;
    SampleClip(clip, 10.0, pose);
    EXPECT_EQ(pose.translation, vec3(4.0f, -2.0f, 8.0f));
    SampleClip(clip, -1.0, pose);
    EXPECT_EQ(pose.translation, vec3(0.0f));
}

TEST(KeyframeTrackTest, LoopingClipWrapsTimeByItsDuration) {
    KeyframeClip clip;
    clip.translation = TwoKeys(Interpolation::kLinear);
    clip.wrap = WrapMode::kLoop;
    EXPECT_EQ(ClipTime(clip, 5.0), 2.0f);
    EXPECT_EQ(ClipTime(clip, -1.0), 2.0f);
    LocalTransform pose;
    SampleClip(clip, 3.0 * 7 + 2.0, pose);
    EXPECT_EQ(pose.translation, vec3(2.0f, -1.0f, 4.0f));
}

TEST(KeyframeTrackTest, ClipLeavesChannelsWithoutKeysAlone) {
    KeyframeClip clip;
    clip.scale.times = {0.0f};
    clip.scale.values = {vec3(3.0f)};
    LocalTransform pose;
    pose.translation = vec3(7.0f);
    SampleClip(clip, 0.5, pose);
    EXPECT_EQ(pose.translation, vec3(7.0f));
    EXPECT_EQ(pose.scale, vec3(3.0f));
    EXPECT_EQ(pose.rotation, glm::identity<glm::quat>());
}

TEST(KeyframeTrackTest, ValidateClipNamesTheTrackAndTheKey) {
    KeyframeClip clip;
    EXPECT_EQ(ValidateClip(clip), "");
    clip.rotation.times = {0.0f, 1.0f, 1.0f};
    clip.rotation.values.assign(3, glm::identity<glm::quat>());
    EXPECT_EQ(ValidateClip(clip), "rotation: key times must increase strictly (key 2)");
    clip.rotation.values.pop_back();
    EXPECT_EQ(ValidateClip(clip), "rotation: 3 key times but 2 values");
}

// glTF 2.0 Appendix C at u = (t - t_k) / td: p = h00 v_k + td h10 b_k + h01 v_k+1 + td h11 a_k+1
// with h00 = 2u^3 - 3u^2 + 1, h10 = u^3 - 2u^2 + u, h01 = -2u^3 + 3u^2, h11 = u^3 - u^2.
// Keys at t = 1 and 3 (td = 2): v = (0,0,0) then (4,-2,8); b_0 = (1,0,0), a_1 = (0,2,0). The
// first key's in-tangent and the last key's out-tangent are never used: they hold nonsense here.
Vec3Track CubicKeys() {
    Vec3Track track = TwoKeys(Interpolation::kCubicSpline);
    track.inTangents = {vec3(100.0f), vec3(0.0f, 2.0f, 0.0f)};
    track.outTangents = {vec3(1.0f, 0.0f, 0.0f), vec3(-100.0f)};
    return track;
}

TEST(KeyframeTrackTest, CubicSplineMidpointFollowsTheSpecificationsHermiteFormula) {
    // u = 0.5: h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = -0.125.
    // p = 0.5 (4,-2,8) + 2 (0.125) (1,0,0) + 2 (-0.125) (0,2,0) = (2.25, -1.5, 4).
    const vec3 p = SampleTrack(CubicKeys(), 2.0f);
    EXPECT_NEAR(p.x, 2.25f, 1e-6f);
    EXPECT_NEAR(p.y, -1.5f, 1e-6f);
    EXPECT_NEAR(p.z, 4.0f, 1e-6f);
}

TEST(KeyframeTrackTest, CubicSplineQuarterWayIsNotLinear) {
    // u = 0.25: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875.
    // p = 0.15625 (4,-2,8) + 2 (0.140625) (1,0,0) + 2 (-0.046875) (0,2,0) = (0.90625, -0.5, 1.25);
    // linear interpolation would give (1, -0.5, 2).
    const vec3 p = SampleTrack(CubicKeys(), 1.5f);
    EXPECT_NEAR(p.x, 0.90625f, 1e-6f);
    EXPECT_NEAR(p.y, -0.5f, 1e-6f);
    EXPECT_NEAR(p.z, 1.25f, 1e-6f);
}

TEST(KeyframeTrackTest, CubicSplinePassesThroughItsKeysWithTheirTangentsAsSlopes) {
    const Vec3Track track = CubicKeys();
    EXPECT_EQ(SampleTrack(track, 1.0f), vec3(0.0f));
    EXPECT_EQ(SampleTrack(track, 3.0f), vec3(4.0f, -2.0f, 8.0f));
    // dp/dt leaving key 0 is b_0 and arriving at key 1 is a_1 (the tangents are per second).
    const float h = 1e-3f;
    const vec3 leaving = (SampleTrack(track, 1.0f + h) - SampleTrack(track, 1.0f)) / h;
    const vec3 arriving = (SampleTrack(track, 3.0f) - SampleTrack(track, 3.0f - h)) / h;
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(leaving[c], vec3(1.0f, 0.0f, 0.0f)[c], 2e-2f) << c;
        EXPECT_NEAR(arriving[c], vec3(0.0f, 2.0f, 0.0f)[c], 2e-2f) << c;
    }
}

TEST(KeyframeTrackTest, CubicSplineRotationIsNormalisedAfterTheHermiteBlend) {
    QuatTrack track;
    track.times = {0.0f, 1.0f};  // td = 1
    const float s = std::sqrt(0.5f);
    // glm::quat(w, x, y, z): identity, then 90 degrees about +Y.
    track.values = {glm::quat(1, 0, 0, 0), glm::quat(s, 0, s, 0)};
    track.interpolation = Interpolation::kCubicSpline;
    track.inTangents = {glm::quat(0, 0, 0, 0), glm::quat(0, 0, 0, 0)};
    track.outTangents = {glm::quat(0, 0, 1, 0), glm::quat(0, 0, 0, 0)};  // b_0 = (0, 1, 0, 0) xyzw
    // u = 0.5: q = 0.5 (0,0,0,1) + 0.125 (0,1,0,0) + 0.5 (0,s,0,s) = (0, 0.5 s + 0.125, 0, 0.5 +
    // 0.5 s) in xyzw, then divided by its length.
    const float y = 0.5f * s + 0.125f, w = 0.5f + 0.5f * s;
    const float length = std::sqrt(y * y + w * w);
    const glm::quat q = SampleTrack(track, 0.5f);
    EXPECT_NEAR(q.x, 0.0f, 1e-6f);
    EXPECT_NEAR(q.y, y / length, 1e-6f);
    EXPECT_NEAR(q.z, 0.0f, 1e-6f);
    EXPECT_NEAR(q.w, w / length, 1e-6f);
    EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f);
    // u = 0.25 with b_0 = 0 instead: h00 = 0.84375, h01 = 0.15625, so the turn is
    // 2 atan2(0.15625 s, 0.84375 + 0.15625 s) = 13.21 degrees, not Nlerp's 21.6.
    track.outTangents[0] = glm::quat(0, 0, 0, 0);
    const float expected = glm::degrees(2.0f * std::atan2(0.15625f * s, 0.84375f + 0.15625f * s));
    EXPECT_NEAR(AngleDegrees(SampleTrack(track, 0.25f)), expected, 1e-4f);
    EXPECT_NEAR(expected, 13.21f, 0.01f);
}

TEST(KeyframeTrackTest, WeightsTrackInterpolatesEveryWeightOfAKey) {
    WeightsTrack track;
    track.count = 2;
    track.times = {0.0f, 2.0f};
    track.values = {0.0f, 1.0f, 1.0f, 0.0f};
    float w[2];
    track.interpolation = Interpolation::kLinear;
    SampleTrack(track, 0.5f, w);
    EXPECT_FLOAT_EQ(w[0], 0.25f);
    EXPECT_FLOAT_EQ(w[1], 0.75f);
    track.interpolation = Interpolation::kStep;
    SampleTrack(track, 1.9f, w);
    EXPECT_EQ(w[0], 0.0f);
    EXPECT_EQ(w[1], 1.0f);
    SampleTrack(track, 5.0f, w);
    EXPECT_EQ(w[0], 1.0f);
    EXPECT_EQ(w[1], 0.0f);
    // Cubic with zero tangents at u = 0.25 (t = 0.5): h01 = 0.15625 of the way.
    track.interpolation = Interpolation::kCubicSpline;
    track.inTangents.assign(4, 0.0f);
    track.outTangents.assign(4, 0.0f);
    SampleTrack(track, 0.5f, w);
    EXPECT_FLOAT_EQ(w[0], 0.15625f);
    EXPECT_FLOAT_EQ(w[1], 0.84375f);
    // Weight 0 leaves key 0 at slope 1 per second: + td h10 b = 2 (0.140625) = 0.28125.
    track.outTangents[0] = 1.0f;
    SampleTrack(track, 0.5f, w);
    EXPECT_FLOAT_EQ(w[0], 0.15625f + 0.28125f);
}

TEST(KeyframeTrackTest, ValidateClipChecksTangentAndWeightCounts) {
    KeyframeClip clip;
    clip.translation = CubicKeys();
    EXPECT_EQ(ValidateClip(clip), "");
    clip.translation.inTangents.pop_back();
    EXPECT_EQ(ValidateClip(clip), "translation: 2 values but 1 in-tangents and 2 out-tangents");
    clip.translation.interpolation = Interpolation::kLinear;  // tangents of a linear track: unused
    EXPECT_EQ(ValidateClip(clip), "");
    clip.weights.count = 2;
    clip.weights.times = {0.0f, 1.0f};
    clip.weights.values = {0.0f, 1.0f, 1.0f};
    EXPECT_EQ(ValidateClip(clip), "weights: 2 key times but 3 weights");
    clip.weights.values.push_back(0.0f);
    EXPECT_EQ(ValidateClip(clip), "");
    EXPECT_EQ(clip.Duration(), 3.0f);
    clip.weights.times = {0.0f, 4.0f};
    EXPECT_EQ(clip.Duration(), 4.0f);
}

}  // namespace
}  // namespace rtrt::physics
