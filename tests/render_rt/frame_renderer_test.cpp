// The frame-renderer seam on the CPU back end, over a hand-made scene (render_rt alone): it
// traces what RenderRaw traces over the same LBVH, follows changed records by refitting, rebuilds
// on a topology change, leaves an unchanged scene alone, picks against what it traced, and
// counts frames and rays.
#include "engine/render_rt/frame_renderer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>

#include "engine/render_rt/renderer.h"
#include "tests/render_rt/frame_renderer_checks.h"

namespace rtrt {
namespace {

using test::ExpectShrunkSceneLeftAloneWhenUnchanged;
using test::kSide;
using test::MoveInstance;
using test::Small;
using test::SphereGrid;

// The scene traced with its own TLAS set to a fresh LBVH over its instances: the reference.
Image ReferenceImage(RenderScene scene, RenderStats* stats = nullptr) {
    scene.SetTlas(
        BuildTlas(scene.instances, std::vector<Aabb>{scene.blases[0]->bounds}, TlasBuilder::kLbvh));
    return RenderRaw(scene, Small(), stats);
}

bool SamePixels(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(vec3)) == 0;
}

TEST(CpuFrameRenderer, TracesWhatRenderRawTracesOverTheSameLbvh) {
    const RenderScene scene = SphereGrid();
    const std::unique_ptr<FrameRenderer> renderer = MakeFrameRenderer(Backend::kCpu, scene);
    EXPECT_EQ(renderer->Kind(), Backend::kCpu);
    EXPECT_EQ(renderer->DeviceFrame(), nullptr);
    Image image;
    RenderStats stats, reference;
    renderer->Trace(scene, Small(), &image, &stats);
    EXPECT_TRUE(SamePixels(image, ReferenceImage(scene, &reference)));
    EXPECT_EQ(stats.rays, reference.rays);
    EXPECT_EQ(renderer->Times().frame, 1u);
    EXPECT_EQ(renderer->Times().rays, reference.rays);
    EXPECT_TRUE(renderer->Times().tlasRebuilt);
}

TEST(CpuFrameRenderer, FollowsChangedRecordsByRefitting) {
    RenderScene scene = SphereGrid();
    const std::unique_ptr<FrameRenderer> renderer =
        MakeFrameRenderer(Backend::kCpu, scene, TlasPolicy::RefitWhileGood());
    const Tlas before = renderer->CurrentTlas();
    MoveInstance(scene, 12, vec3(0.5f, 0.25f, 1.0f));  // the centre sphere, a small move
    const uint32_t changed[] = {12};
    renderer->Update(scene, {changed, false});
    Image image;
    renderer->Trace(scene, Small(), &image);
    EXPECT_FALSE(renderer->Times().tlasRebuilt);
    // Same topology: the same instances in the same leaves.
    EXPECT_EQ(TlasLeafInstances(renderer->CurrentTlas()), TlasLeafInstances(before));
    EXPECT_TRUE(SamePixels(image, ReferenceImage(scene)));
}

// The runtime's policy: a moved instance means a fresh tree (at any size), which holds the moved
// sphere's new box in a leaf and traces what the reference traces.
TEST(CpuFrameRenderer, RebuildsASmallSceneWhenAnInstanceMoved) {
    RenderScene scene = SphereGrid();
    const std::unique_ptr<FrameRenderer> renderer = MakeFrameRenderer(Backend::kCpu, scene);
    MoveInstance(scene, 12, vec3(0.5f, 0.25f, 1.0f));
    const uint32_t changed[] = {12};
    renderer->Update(scene, {changed, false});
    Image image;
    renderer->Trace(scene, Small(), &image);
    EXPECT_TRUE(renderer->Times().tlasRebuilt);
    EXPECT_TRUE(SamePixels(image, ReferenceImage(scene)));
}

TEST(CpuFrameRenderer, LeavesAnUnchangedSceneAlone) {
    const RenderScene scene = SphereGrid();
    const std::unique_ptr<FrameRenderer> renderer = MakeFrameRenderer(Backend::kCpu, scene);
    const Tlas before = renderer->CurrentTlas();
    renderer->Update(scene, SceneChanges{});
    renderer->Trace(scene, Small(), nullptr);
    EXPECT_EQ(renderer->Times().frame, 1u);
    EXPECT_EQ(renderer->Times().tlasMs, 0.0);
    EXPECT_FALSE(renderer->Times().tlasRebuilt);
    const Tlas after = renderer->CurrentTlas();
    ASSERT_EQ(after.nodes.size(), before.nodes.size());
    EXPECT_EQ(
        std::memcmp(after.nodes.data(), before.nodes.data(), before.nodes.size() * sizeof(BvhNode)),
        0);
}

TEST(CpuFrameRenderer, RebuildsWhenInstancesAreAdded) {
    RenderScene scene = SphereGrid();
    const std::unique_ptr<FrameRenderer> renderer = MakeFrameRenderer(Backend::kCpu, scene);
    const uint32_t added = scene.AddInstance(0, 0, glm::translate(glm::mat4(1.0f), vec3(0, 0, 5)));
    const uint32_t changed[] = {added};
    renderer->Update(scene, {changed, true});
    Image image;
    renderer->Trace(scene, Small(), &image);
    EXPECT_TRUE(renderer->Times().tlasRebuilt);
    EXPECT_EQ(TlasLeafInstances(renderer->CurrentTlas()).size(), scene.instances.size());
    EXPECT_TRUE(SamePixels(image, ReferenceImage(scene)));
}

// A ray down -z through sphere (i, j)'s centre hits it at distance 30 - 1 from z = 30.
TEST(CpuFrameRenderer, PicksAgainstWhatItTraced) {
    const RenderScene scene = SphereGrid();
    const std::unique_ptr<FrameRenderer> renderer = MakeFrameRenderer(Backend::kCpu, scene);
    for (uint32_t instance : {0u, 7u, 24u}) {
        const vec3 centre(3.0f * (int(instance % kSide) - 2), 3.0f * (int(instance / kSide) - 2),
                          0.0f);
        const Ray ray{centre + vec3(0, 0, 30), kInfinity, vec3(0, 0, -1), 0.0f};
        SceneHit hit{};
        ASSERT_TRUE(renderer->Pick(ray, &hit));
        EXPECT_EQ(hit.instance, instance);
        EXPECT_FLOAT_EQ(hit.t, 29.0f);
    }
    const Ray miss{vec3(1.5f, 1.5f, 30), kInfinity, vec3(0, 0, -1), 0.0f};
    SceneHit hit{};
    EXPECT_FALSE(renderer->Pick(miss, &hit));
}

TEST(CpuFrameRenderer, ShrunkSceneLeftAloneWhenUnchanged) {
    ExpectShrunkSceneLeftAloneWhenUnchanged(Backend::kCpu);
}

TEST(FrameRendererFactory, CudaWithoutADeviceSaysWhy) {
    std::string why;
    if (CudaBackendAvailable(&why)) GTEST_SKIP() << "a CUDA device is present";
    try {
        MakeFrameRenderer(Backend::kCuda, SphereGrid());
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("use the CPU back end"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace rtrt
