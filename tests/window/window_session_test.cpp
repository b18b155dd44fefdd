// Checks what the scripted window session (session.script, run by ctest window_session under
// Xvfb) showed: its screenshots are read back from the window's framebuffer, so they show what
// the display path (CPU upload, or CUDA-GL interop on a GPU) really put on screen.
#include <gtest/gtest.h>

#include <cstdlib>

#include "engine/render_rt/renderer.h"
#include "game/assets/image_io.h"
#include "game/scene/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

constexpr uint32_t kWidth = 320, kHeight = 180;

std::string ShotDir() {
    const char* dir = std::getenv("RTRT_WINDOW_SHOTS");
    return dir ? dir : ".";
}

Image Shot(const std::string& name) {
    const Image image = ReadImage(ShotDir() + "/" + name);
    EXPECT_EQ(image.width, kWidth);
    EXPECT_EQ(image.height, kHeight);
    return image;
}

bool IsSphereRed(vec3 c) { return c.x > 0.35f && c.x > 2.0f * c.y && c.x > 2.0f * c.z; }

class WindowSession : public ::testing::Test {
  protected:
    void SetUp() override { RTRT_REQUIRE_MODEL(teapot, "teapot.inc"); }
};

// The first frame shown equals the CPU render of the scene — the window shows what the tracer
// made, the right way up. With the CPU back end to 8-bit rounding (GL converts floats to bytes
// itself); with CUDA (RTRT_WINDOW_BACKEND=cuda: the frame came through CUDA-GL interop) within
// the GPU-vs-CPU tolerance of gpu_vs_cpu_test.cpp: RMSE <= 1/255, at most 0.5% of pixels off by
// more than 4/255.
TEST_F(WindowSession, FirstFrameIsTheSceneRender) {
    const char* backend = std::getenv("RTRT_WINDOW_BACKEND");
    const bool cuda = backend && std::string(backend) == "cuda";
    const LoadedScene scene = LoadSceneFile(test::SourcePath("assets/scenes/teapot_shadow.json"));
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.maxDepth = scene.scene.maxDepth;
    const Image expected = RenderRaw(scene.scene, s);
    const Image shown = Shot("initial.ppm");
    ASSERT_EQ(shown.pixels.size(), expected.pixels.size());
    size_t off = 0;
    double sum = 0.0;
    for (size_t i = 0; i < shown.pixels.size(); ++i) {
        float worst = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float d =
                std::abs(std::clamp(expected.pixels[i][c], 0.0f, 1.0f) - shown.pixels[i][c]);
            worst = std::max(worst, d);
            sum += double(d) * d;
        }
        off += worst > (cuda ? 4.0f : 1.5f) / 255.0f;
    }
    if (cuda) {
        EXPECT_LE(std::sqrt(sum / (3.0 * shown.pixels.size())), 1.0 / 255.0);
        EXPECT_LE(double(off), 0.005 * shown.pixels.size());
    } else {
        EXPECT_EQ(off, 0u);
    }
}

// Key 1 spawned a sphere at the centre; dragging moved it 80 pixels right; F5 turned shadows
// off; Delete removed the picked sphere.
TEST_F(WindowSession, SpawnDragToggleAndDeleteShowOnScreen) {
    const Image initial = Shot("initial.ppm"), spawned = Shot("spawned.ppm"),
                dragged = Shot("dragged.ppm"), noShadows = Shot("no_shadows.ppm"),
                deleted = Shot("deleted.ppm");
    const uint32_t cx = 160, cy = 90;
    EXPECT_FALSE(IsSphereRed(initial.At(cx, cy)));
    EXPECT_TRUE(IsSphereRed(spawned.At(cx, cy)));
    EXPECT_FALSE(IsSphereRed(spawned.At(cx + 80, cy)));
    EXPECT_TRUE(IsSphereRed(dragged.At(cx + 80, cy)));
    EXPECT_FALSE(IsSphereRed(dragged.At(cx, cy)));
    // Without shadows nothing gets darker and the teapot's shadow on the floor lights up.
    size_t brighter = 0, darker = 0;
    for (size_t i = 0; i < dragged.pixels.size(); ++i) {
        const float d = Luminance(noShadows.pixels[i]) - Luminance(dragged.pixels[i]);
        brighter += d > 0.1f;
        darker += d < -1.5f / 255.0f;
    }
    EXPECT_GT(brighter, 200u);
    EXPECT_EQ(darker, 0u);
    EXPECT_FALSE(IsSphereRed(deleted.At(cx + 80, cy)));
}

}  // namespace
}  // namespace rtrt
