// Split-frame rendering (multi_gpu_frame_renderer.h) on the one GPU the test machine has: a
// frame split over two or three renderers of the same device takes every step of the split over
// several GPUs (a scene copy and a TLAS per renderer, the band traces, the gather with
// cudaMemcpyPeerAsync, the TLAS copies, the shares that follow the band times) but peer access
// between two devices. Every frame must equal the single renderer's bit for bit. Label gpu.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <numeric>

#include "engine/render_rt/frame_renderer.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

// edit, if any, changes both worlds before frame 6.
void ExpectSplitFramesEqualWhole(const char* sceneFile, const GpuSplit& split, int frames,
                                 const std::function<void(World&)>& edit = {}) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const LoadedScene loaded =
        LoadSceneFile(test::SourcePath(std::string("assets/scenes/") + sceneFile));
    RenderSettings s;
    s.width = 320;
    s.height = 181;  // not a multiple of the bands' granule
    s.maxDepth = loaded.scene.maxDepth;
    World wholeWorld(loaded);
    World splitWorld(loaded);
    const std::unique_ptr<FrameRenderer> whole =
        MakeFrameRenderer(Backend::kCuda, wholeWorld.Scene());
    const std::unique_ptr<FrameRenderer> parts =
        MakeFrameRenderer(Backend::kCuda, splitWorld.Scene(), {}, {}, split);
    for (int f = 1; f <= frames; ++f) {
        if (edit && f == 6) {
            edit(wholeWorld);
            edit(splitWorld);
        }
        wholeWorld.Advance(1.0f / 60.0f);
        whole->Update(wholeWorld.Scene(), wholeWorld.Changes());
        splitWorld.Advance(1.0f / 60.0f);
        parts->Update(splitWorld.Scene(), splitWorld.Changes());
        // Most frames stay queued (the pipelined loop); every fourth is compared, and every
        // fifth is traced twice, the second time without an update.
        const bool compare = f % 4 == 0;
        Image a, b;
        RenderStats aStats, bStats;
        if (f % 5 == 0) {
            whole->Trace(wholeWorld.Scene(), s, nullptr);
            parts->Trace(splitWorld.Scene(), s, nullptr);
        }
        whole->Trace(wholeWorld.Scene(), s, compare ? &a : nullptr, compare ? &aStats : nullptr);
        parts->Trace(splitWorld.Scene(), s, compare ? &b : nullptr, compare ? &bStats : nullptr);
        if (!compare) continue;
        SCOPED_TRACE("frame " + std::to_string(f));
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(vec3)));
        EXPECT_GT(aStats.rays, 0u);
        EXPECT_EQ(aStats.rays, bStats.rays);
    }
    parts->Finish();
    const FrameTimes& t = parts->Times();
    ASSERT_EQ(t.gpus, split.devices.size());
    EXPECT_EQ(std::accumulate(t.gpuRows.begin(), t.gpuRows.begin() + t.gpus, 0u), s.height);
    for (uint32_t g = 0; g < t.gpus; ++g) {
        EXPECT_GE(t.gpuRows[g], 8u) << "every GPU keeps a granule of rows";
        EXPECT_GT(t.gpuTraceMs[g], 0.0);
    }
    EXPECT_GT(t.traceMs, 0.0);
    // The display GPU's tree is the single renderer's.
    const Tlas wholeTlas = whole->CurrentTlas(), splitTlas = parts->CurrentTlas();
    ASSERT_EQ(wholeTlas.nodes.size(), splitTlas.nodes.size());
    EXPECT_EQ(0, std::memcmp(wholeTlas.nodes.data(), splitTlas.nodes.data(),
                             wholeTlas.nodes.size() * sizeof(BvhNode)));
}

// Skinned walkers: every renderer deforms its own copies of the BLASes.
TEST(MultiGpuFrameRenderer, TwoRenderersOfOneGpuEqualOne) {
    ExpectSplitFramesEqualWhole("demo_crowd.json", {{0, 0}, GpuSplit::Tlas::kBuildOnEach}, 16);
}

// Rigid bodies moving every record; the others copy the display renderer's records and tree.
TEST(MultiGpuFrameRenderer, ThreeRenderersCopyingTheTlasEqualOne) {
    ExpectSplitFramesEqualWhole("demo_physics.json", {{0, 0, 0}, GpuSplit::Tlas::kCopyFromDisplay},
                                16);
}

// Instances removed and spawned (records move, the TLAS is rebuilt for another count), in both
// ways of sharing the TLAS.
void RemoveAndSpawn(World& world) {
    const Instance copied = world.Scene().instances[7];
    ASSERT_TRUE(world.Remove(world.EntityOfInstance(5)));
    EntityDesc desc;
    desc.blasId = copied.blasId;
    desc.materialId = copied.materialId;
    desc.local.translation = vec3(0.5f, 2.0f, 3.0f);
    world.Spawn(desc);
}
TEST(MultiGpuFrameRenderer, CopiedTlasFollowsRemovedAndSpawnedInstances) {
    ExpectSplitFramesEqualWhole("demo_1000_instances.json",
                                {{0, 0}, GpuSplit::Tlas::kCopyFromDisplay}, 12, RemoveAndSpawn);
}
TEST(MultiGpuFrameRenderer, BuiltTlasFollowsRemovedAndSpawnedInstances) {
    ExpectSplitFramesEqualWhole("demo_1000_instances.json", {{0, 0}, GpuSplit::Tlas::kBuildOnEach},
                                12, RemoveAndSpawn);
}

TEST(MultiGpuFrameRenderer, PicksWhatTheDisplayGpuTraced) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const LoadedScene loaded =
        LoadSceneFile(test::SourcePath("assets/scenes/demo_1000_instances.json"));
    World world(loaded);
    const std::unique_ptr<FrameRenderer> whole = MakeFrameRenderer(Backend::kCuda, world.Scene());
    const std::unique_ptr<FrameRenderer> parts =
        MakeFrameRenderer(Backend::kCuda, world.Scene(), {}, {}, {{0, 0}});
    const Camera& c = world.Scene().camera;
    const Ray ray{c.position, 1e30f, glm::normalize(c.forward), 0.0f};
    SceneHit a{}, b{};
    // The centre ray meets an instance (the CPU's depth view of frame 0 says so): two misses
    // would compare two empty hits.
    ASSERT_TRUE(whole->Pick(ray, &a));
    ASSERT_TRUE(parts->Pick(ray, &b));
    EXPECT_EQ(a.instance, b.instance);
    EXPECT_EQ(a.prim, b.prim);
    EXPECT_EQ(a.t, b.t);
}

}  // namespace
}  // namespace rtrt
