// `rtrt bench embree` compares like with like: a frame traced through Embree (EmbreePolicy) is
// rtrt's frame, the same hits shaded the same way, on the direct path (one instance) and the
// instanced one (several instances, rotated and scaled, triangles and spheres), so its time
// measures the traversal and nothing else.
#include "bench/embree/embree_policy.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "bench/embree/embree_scene.h"
#include "engine/render_rt/cpu/trace_tiles.h"
#include "game/assets/image_io.h"
#include "game/assets/procedural_shapes.h"
#include "game/scene/paper_scene.h"

namespace rtrt {
namespace {

constexpr uint32_t kFeatures = kFeatureShadows | kFeatureReflection | kFeatureRefraction;

// Pixels whose 8-bit values differ, and rays traced by each, for the scene through both.
struct Comparison {
    size_t differing = 0;
    uint64_t ourRays = 0, theirRays = 0;
};
Comparison CompareFrames(const RenderScene& scene, uint32_t width, uint32_t height) {
    const EmbreeScene embree(scene);
    EmbreePolicy::scene = embree.Handle();
    const RenderSceneView view = scene.HostView(width, height, 2);
    Image ours(width, height), theirs(width, height);
    Comparison c;
    c.ourRays = TraceTiles<kFeatures, TracePolicy>(view, ViewMode::kShaded, ours);
    c.theirRays = TraceTiles<kFeatures, EmbreePolicy>(view, ViewMode::kShaded, theirs);
    EmbreePolicy::scene = nullptr;
    const std::vector<uint8_t> a = EightBit(ours), b = EightBit(theirs);
    for (size_t i = 0; i < a.size(); i += 3)
        c.differing += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
    return c;
}

TEST(EmbreePolicy, OneInstanceFrameIsRtrtsFrame) {
    const RenderScene scene = MakePaperScene(
        std::make_shared<const Blas>(BuildTriangleBlas(MakeBoxMesh(vec3(2.0f, 1.5f, 1.0f)))));
    const Comparison c = CompareFrames(scene, 320, 180);
    EXPECT_GT(c.ourRays, 320u * 180u);  // shadow and reflection rays too
    EXPECT_EQ(c.ourRays, c.theirRays);
    EXPECT_EQ(c.differing, 0u);
}

TEST(EmbreePolicy, InstancedTrianglesAndSpheresFrameIsRtrtsFrame) {
    RenderScene scene;
    scene.camera = {vec3(0, 3, 12), vec3(0, -0.2f, -1), vec3(0, 1, 0), 45.0f};
    scene.background = vec3(0.2f, 0.3f, 0.5f);
    Material shiny;
    shiny.diffuse = vec3(0.7f, 0.6f, 0.2f);
    shiny.specular = vec3(0.5f);
    shiny.shininess = 40.0f;
    shiny.reflectivity = 0.4f;
    Material matte;
    matte.diffuse = vec3(0.3f, 0.6f, 0.3f);
    const uint32_t shinyId = scene.AddMaterial(shiny), matteId = scene.AddMaterial(matte);
    const uint32_t box =
        scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(MakeBoxMesh(vec3(1.0f)))));
    const uint32_t floor =
        scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(MakePlaneMesh(20, 20))));
    const Sphere balls[] = {{vec3(-1, 0, 0), 0.8f}, {vec3(1.5f, 0.5f, 0.3f), 0.6f}};
    const uint32_t spheres = scene.AddBlas(std::make_shared<const Blas>(BuildSphereBlas(balls)));
    scene.AddInstance(floor, matteId, glm::translate(glm::mat4(1.0f), vec3(0, -1, 0)));
    for (int i = 0; i < 3; ++i) {
        glm::mat4 m = glm::translate(glm::mat4(1.0f), vec3(-3.0f + 3.0f * float(i), 0.2f, -1.0f));
        m = glm::rotate(m, 0.4f + 0.5f * float(i), glm::normalize(vec3(1, 2, 0.5f)));
        scene.AddInstance(box, i == 1 ? shinyId : matteId,
                          glm::scale(m, vec3(1.0f + 0.2f * float(i))));
    }
    scene.AddInstance(spheres, shinyId, glm::translate(glm::mat4(1.0f), vec3(0, 0.5f, 2.5f)));
    scene.lights.push_back(
        {glm::normalize(vec3(1.0f, 2.0f, 1.0f)), LightType::kDirectional, vec3(1.0f), 0.0f});
    scene.BuildTlas();
    const Comparison c = CompareFrames(scene, 320, 180);
    EXPECT_EQ(c.ourRays, c.theirRays);
    // The two triangle tests differ in their last bits: a pixel on a silhouette may round
    // the other way, no more.
    EXPECT_LE(c.differing, 320u * 180u / 500u);
}

}  // namespace
}  // namespace rtrt
