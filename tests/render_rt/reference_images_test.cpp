// Reference-image regression: scenes rendered on the CPU compared with images rendered by rtrt
// and committed under tests/reference/ (tools/update_reference_images.sh regenerates them).
// Tolerance: RMSE over all channels <= 1/255, and at most 0.1% of pixels off by more than
// 8/255 in any channel; the CPU back end is deterministic, so on the same build the images are
// identical and the tolerance absorbs compiler and libm differences between machines.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "engine/render_rt/renderer.h"
#include "game/assets/image_io.h"
#include "game/scene/default_scene.h"
#include "game/scene/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

constexpr uint32_t kWidth = 200, kHeight = 150;

struct Difference {
    double rmse = 0.0;
    double outlierFraction = 0.0;
};

Difference Compare(const Image& a, const Image& b) {
    double sum = 0.0;
    size_t outliers = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        // Compare what a PNG stores: 8-bit values of clamped colours.
        float worst = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float va = std::round(std::clamp(a.pixels[i][c], 0.0f, 1.0f) * 255.0f) / 255.0f;
            const float vb = b.pixels[i][c];
            sum += double(va - vb) * (va - vb);
            worst = std::max(worst, std::abs(va - vb));
        }
        outliers += worst > 8.0f / 255.0f;
    }
    return {std::sqrt(sum / (3.0 * a.pixels.size())), double(outliers) / a.pixels.size()};
}

void ExpectMatchesReference(const RenderScene& scene, const std::string& name) {
    if (!CanReadImages()) GTEST_SKIP() << "this build has no OpenImageIO to read the references";
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.maxDepth = scene.maxDepth;
    const Image rendered = Render(scene, s, Backend::kCpu);
    const Image reference = ReadImage(test::SourcePath("tests/reference/" + name + ".png"));
    ASSERT_EQ(reference.width, kWidth);
    ASSERT_EQ(reference.height, kHeight);
    const Difference d = Compare(rendered, reference);
    EXPECT_LE(d.rmse, 1.0 / 255.0) << name;
    EXPECT_LE(d.outlierFraction, 0.001) << name;
}

TEST(ReferenceImages, DefaultScene) { ExpectMatchesReference(MakeDefaultScene(), "default"); }

TEST(ReferenceImages, ReflectiveSphere) {
    ExpectMatchesReference(
        LoadSceneFile(test::SourcePath("assets/scenes/reflective_sphere.json")).scene,
        "reflective_sphere");
}

TEST(ReferenceImages, RefractiveSphere) {
    ExpectMatchesReference(
        LoadSceneFile(test::SourcePath("assets/scenes/refractive_sphere.json")).scene,
        "refractive_sphere");
}

TEST(ReferenceImages, TeapotShadow) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    ExpectMatchesReference(
        LoadSceneFile(test::SourcePath("assets/scenes/teapot_shadow.json")).scene, "teapot_shadow");
}

// The test itself can fail: a changed scene differs from its reference.
TEST(ReferenceImages, ADifferentSceneDoesNotMatch) {
    if (!CanReadImages()) GTEST_SKIP() << "this build has no OpenImageIO to read the references";
    RenderScene scene = MakeDefaultScene();
    scene.background = vec3(1, 0, 0);
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    const Difference d = Compare(Render(scene, s, Backend::kCpu),
                                 ReadImage(test::SourcePath("tests/reference/default.png")));
    EXPECT_GT(d.rmse, 1.0 / 255.0);
}

}  // namespace
}  // namespace rtrt

namespace rtrt {
namespace {

// The CPU back end gives the same image, bit for bit, on every run: tiles are independent and
// each pixel's computation does not depend on which thread ran it or when.
TEST(Determinism, SameSceneSameImageEveryRun) {
    const RenderScene scene = MakeDefaultScene();
    RenderSettings s;
    s.width = 160;
    s.height = 90;
    s.maxDepth = 6;
    const Image first = RenderRaw(scene, s);
    for (int run = 0; run < 3; ++run) {
        const Image again = RenderRaw(scene, s);
        ASSERT_EQ(std::memcmp(first.pixels.data(), again.pixels.data(),
                              first.pixels.size() * sizeof(vec3)),
                  0)
            << "run " << run;
    }
}

}  // namespace
}  // namespace rtrt
