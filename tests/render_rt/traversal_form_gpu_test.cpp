// The GPU's two traversals of a scene of many instances (traversal/traversal_form.h) give the
// same frames bit for bit, so that the frame renderer may switch between them as it measures
// them: played demos traced with the nested form, the single loop and the renderer's own choice.
// Label gpu.
#include <gtest/gtest.h>

#include <cstring>

#include "engine/render_rt/frame_renderer.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

void ExpectFormsTraceTheSameFrames(const char* sceneFile) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const LoadedScene loaded =
        LoadSceneFile(test::SourcePath(std::string("assets/scenes/") + sceneFile));
    ASSERT_NE(loaded.scene.Features() & kFeatureManyInstances, 0u) << "a scene of many instances";
    RenderSettings s;
    s.width = 320;
    s.height = 180;
    s.maxDepth = loaded.scene.maxDepth;
    const TraversalForm forms[] = {TraversalForm::kNested, TraversalForm::kSingleLoop,
                                   TraversalForm::kAuto};
    World worlds[] = {World(loaded), World(loaded), World(loaded)};
    std::unique_ptr<FrameRenderer> renderers[3];
    for (int k = 0; k < 3; ++k) renderers[k] = MakeFrameRenderer(Backend::kCuda, worlds[k].Scene());
    uint32_t autoSingle = 0, autoNested = 0;
    for (int f = 1; f <= 24; ++f) {
        Image images[3];
        RenderStats stats[3];
        const bool compare = f % 3 == 0;
        for (int k = 0; k < 3; ++k) {
            worlds[k].Advance(1.0f / 60.0f);
            renderers[k]->Update(worlds[k].Scene(), worlds[k].Changes());
            RenderSettings settings = s;
            settings.traversal = forms[k];
            renderers[k]->Trace(worlds[k].Scene(), settings, compare ? &images[k] : nullptr,
                                compare ? &stats[k] : nullptr);
            renderers[k]->Finish();
            const FrameTimes& t = renderers[k]->Times();
            ASSERT_EQ(t.frame, uint64_t(f));
            if (forms[k] != TraversalForm::kAuto)
                EXPECT_EQ(t.singleLoop, forms[k] == TraversalForm::kSingleLoop);
            else
                ++(t.singleLoop ? autoSingle : autoNested);
        }
        if (!compare) continue;
        SCOPED_TRACE("frame " + std::to_string(f));
        for (int k = 1; k < 3; ++k) {
            ASSERT_EQ(images[0].pixels.size(), images[k].pixels.size());
            EXPECT_EQ(0, std::memcmp(images[0].pixels.data(), images[k].pixels.data(),
                                     images[0].pixels.size() * sizeof(vec3)))
                << TraversalFormName(forms[k]) << " against nested";
            EXPECT_EQ(stats[0].rays, stats[k].rays);
        }
        EXPECT_GT(stats[0].rays, 0u);
    }
    // The choice's first trial took both forms.
    EXPECT_GE(autoSingle, TraversalChooser::kTrialFrames / 2);
    EXPECT_GE(autoNested, TraversalChooser::kTrialFrames / 2);
}

TEST(TraversalForms, TraceTheSameFramesOfFallingBodies) {
    ExpectFormsTraceTheSameFrames("demo_physics.json");
}

TEST(TraversalForms, TraceTheSameFramesOfManyModels) {
    ExpectFormsTraceTheSameFrames("demo_1000_instances.json");
}

// Skinned walkers: the BLASes deform every frame.
TEST(TraversalForms, TraceTheSameFramesOfACrowd) {
    ExpectFormsTraceTheSameFrames("demo_crowd.json");
}

}  // namespace
}  // namespace rtrt
