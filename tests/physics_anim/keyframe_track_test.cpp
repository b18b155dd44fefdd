// Keyframe tracks: exact values for step, linear and slerp interpolation, clamping and looping.
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

}  // namespace
}  // namespace rtrt::physics
