#pragma once
// The frame-renderer checks both back ends run: a grid of spheres, small settings, and the shrunk
// scene that must then be left alone (frame_renderer_test.cpp on the CPU, frame_renderer_gpu_test
// .cpp on the GPU, whose suite the GPU machine runs).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <memory>

#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"

namespace rtrt::test {

constexpr int kSide = 5;  // a 5 x 5 grid of unit spheres, 3 apart, in z = 0

inline RenderScene SphereGrid() {
    RenderScene scene;
    const Sphere sphere{vec3(0.0f), 1.0f};
    scene.AddBlas(std::make_shared<const Blas>(BuildSphereBlas(std::span(&sphere, 1))));
    scene.AddMaterial(Material{});
    scene.lights.push_back(Light{glm::normalize(vec3(1, 2, 3)), LightType::kDirectional, vec3(1)});
    for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i)
            scene.AddInstance(
                0, 0, glm::translate(glm::mat4(1.0f), vec3(3.0f * (i - 2), 3.0f * (j - 2), 0)));
    scene.camera.position = vec3(0, 0, 30);
    return scene;
}

inline RenderSettings Small() {
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.maxDepth = 2;
    return s;
}

inline void MoveInstance(RenderScene& scene, uint32_t i, vec3 to) {
    const glm::mat4 m = glm::translate(glm::mat4(1.0f), to);
    SetTransform(scene.instances[i], m);
}

// A scene that shrinks to the policy's small-scene size must then leave unchanged frames alone,
// even when its last SAH cost (which the device learns one update late) was past the bound: with
// maxSahGrowth -0.5 every update of the larger scene is past it. On both back ends.
inline void ExpectShrunkSceneLeftAloneWhenUnchanged(Backend backend) {
    RenderScene scene = SphereGrid();
    TlasPolicy policy;
    policy.maxSahGrowth = -0.5f;
    policy.rebuildChangedUpTo = kSide * kSide - 1;
    const std::unique_ptr<FrameRenderer> renderer = MakeFrameRenderer(backend, scene, policy);
    for (int f = 1; f <= 2; ++f) {
        MoveInstance(scene, 12, vec3(0.5f * float(f), 0.0f, 1.0f));
        const uint32_t changed[] = {12};
        renderer->Update(scene, {changed, false});
        renderer->Trace(scene, Small(), nullptr);
        renderer->Finish();
        EXPECT_TRUE(renderer->Times().tlasRebuilt) << "frame " << f << " drifted past the bound";
    }
    scene.instances.pop_back();
    renderer->Update(scene, {{}, true});
    renderer->Trace(scene, Small(), nullptr);
    renderer->Finish();
    EXPECT_TRUE(renderer->Times().tlasRebuilt);
    for (int f = 0; f < 3; ++f) {
        renderer->Update(scene, SceneChanges{});
        renderer->Trace(scene, Small(), nullptr);
        renderer->Finish();
        EXPECT_FALSE(renderer->Times().tlasRebuilt) << "unchanged frame " << f;
    }
    MoveInstance(scene, 3, vec3(0.0f, 0.0f, 2.0f));
    const uint32_t changed[] = {3};
    renderer->Update(scene, {changed, false});
    renderer->Trace(scene, Small(), nullptr);
    renderer->Finish();
    EXPECT_TRUE(renderer->Times().tlasRebuilt);
}

}  // namespace rtrt::test
