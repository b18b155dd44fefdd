// The primary-hit kernel (engine/render_rt/cuda/trace_launch.cuh): lanes that take up new rays as
// theirs finish must find the hits each pixel's own traversal finds.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "engine/render_rt/cuda/cuda_trace.h"
#include "engine/render_rt/cuda/device_scene.h"
#include "engine/render_rt/pixel_kernel.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

struct Traced {
    std::vector<vec3> pixels;
    unsigned long long rays = 0;
};

Traced TraceBand(const RenderSceneView& view, const RenderSettings& settings, uint32_t features,
                 RowBand rows, PrimaryHitScratch primary) {
    const size_t pixels = size_t(settings.width) * settings.height;
    DeviceBuffer<vec3> frame;
    frame.Resize(pixels);
    RT_CUDA_CHECK(cudaMemset(frame.Data(), 0, pixels * sizeof(vec3)));
    DeviceBuffer<unsigned long long> rays;
    rays.Resize(1);
    RT_CUDA_CHECK(cudaMemset(rays.Data(), 0, sizeof(unsigned long long)));
    LaunchTrace(view, settings.view, features, frame.Data(), rays.Data(), 0, rows, primary);
    RT_CUDA_CHECK(cudaDeviceSynchronize());
    Traced traced;
    traced.pixels.resize(pixels);
    frame.Download(traced.pixels);
    rays.Download(std::span<unsigned long long>(&traced.rays, 1));
    return traced;
}

// demo_physics after half a second: 460 spheres and boxes in the air and on a reflective floor,
// a scene of many instances (the single two-level loop) with spheres and triangles. The frame is
// traced with and without the kernel, in every view that uses it, with one and four samples per
// pixel, over a band of rows that starts and ends inside the 8 x 4 tiles the kernel hands out,
// on a frame whose width is no multiple of 8.
TEST(GpuPrimaryHits, SameFrameAsEachPixelTracingItsOwn) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const LoadedScene loaded = LoadSceneFile(test::SourcePath("assets/scenes/demo_physics.json"));
    World world(loaded);
    for (int f = 0; f < 30; ++f) world.Advance(1.0f / 60.0f);
    const RenderScene& scene = world.Scene();
    ASSERT_NE(scene.Features() & kFeatureManyInstances, 0u);
    DeviceStaticScene device(scene);
    PrimaryHitBuffers buffers;
    const RowBand rows{13, 110};
    for (const ViewMode mode : {ViewMode::kShaded, ViewMode::kNormals, ViewMode::kDepth}) {
        for (const uint32_t samples : {1u, 4u}) {
            RenderSettings settings;
            settings.width = 203;
            settings.height = 117;
            settings.maxDepth = scene.maxDepth;
            settings.view = mode;
            settings.samplesPerPixel = samples;
            SCOPED_TRACE("view " + std::to_string(int(mode)) + ", " + std::to_string(samples) +
                         " samples");
            const uint32_t features =
                EffectiveFeatures(scene.Features(), settings.enabledFeatures, mode);
            const RenderSceneView view = device.View(scene, settings);
            const Traced own = TraceBand(view, settings, features, rows, {});
            const Traced first =
                TraceBand(view, settings, features, rows,
                          buffers.For(features, settings.width, settings.height, 0));
            ASSERT_EQ(own.pixels.size(), first.pixels.size());
            EXPECT_EQ(0, std::memcmp(own.pixels.data(), first.pixels.data(),
                                     own.pixels.size() * sizeof(vec3)));
            EXPECT_EQ(own.rays, first.rays);
            // The band was traced, and nothing outside it.
            size_t written = 0, outside = 0;
            for (uint32_t y = 0; y < settings.height; ++y)
                for (uint32_t x = 0; x < settings.width; ++x) {
                    const bool set = first.pixels[size_t(y) * settings.width + x] != vec3(0.0f);
                    (y >= rows.begin && y < rows.end ? written : outside) += set;
                }
            EXPECT_GT(written, size_t(settings.width) * (rows.end - rows.begin) / 2);
            EXPECT_EQ(outside, 0u);
        }
    }
}

}  // namespace
}  // namespace rtrt
