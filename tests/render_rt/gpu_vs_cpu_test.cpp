// GPU images equal CPU images (the reference) within a stated tolerance, for every verification
// and demo scene (the demos played through the GPU frame loop): RMSE <= 1/255 and at most 0.5% of
// pixels off by more than 4/255 in any channel. The two back ends run the same RT_HD code; the
// tolerance covers float rounding (the GPU contracts multiply-adds outside the watertight edge
// tests, and its powf/sqrtf round differently), which can flip a pixel on a silhouette or shadow
// edge. Label gpu: CI has no GPU and skips these.
#include <gtest/gtest.h>

#include <cstring>
#include <optional>

#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"
#include "game/assets/teapot.h"
#include "game/runtime/world.h"
#include "game/scene/default_scene.h"
#include "game/scene/paper_scene.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

void ExpectImagesClose(const Image& cpu, const Image& gpu, const RenderStats& cpuStats,
                       const RenderStats& gpuStats) {
    ASSERT_EQ(cpu.pixels.size(), gpu.pixels.size());
    double sum = 0.0;
    size_t outliers = 0;
    for (size_t i = 0; i < cpu.pixels.size(); ++i) {
        float worst = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float a = std::clamp(cpu.pixels[i][c], 0.0f, 1.0f);
            const float b = std::clamp(gpu.pixels[i][c], 0.0f, 1.0f);
            sum += double(a - b) * (a - b);
            worst = std::max(worst, std::abs(a - b));
        }
        outliers += worst > 4.0f / 255.0f;
    }
    const double rmse = std::sqrt(sum / (3.0 * cpu.pixels.size()));
    EXPECT_LE(rmse, 1.0 / 255.0);
    EXPECT_LE(double(outliers), 0.005 * cpu.pixels.size()) << outliers << " pixels differ";
    // Ray counts differ only where a pixel's path differs.
    EXPECT_NEAR(double(gpuStats.rays), double(cpuStats.rays), 0.005 * double(cpuStats.rays));
}

// exposure scales both images first (scenes in physical units: ExposeForKeyLight).
void ExpectGpuMatchesCpu(const RenderScene& scene, ViewMode view = ViewMode::kShaded,
                         float exposure = 1.0f) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    RenderSettings s;
    s.width = 320;
    s.height = 240;
    s.maxDepth = scene.maxDepth;
    s.view = view;
    RenderStats cpuStats, gpuStats;
    Image cpu = RenderRaw(scene, s, &cpuStats);
    Image gpu = RenderRawCuda(scene, s, &gpuStats);
    for (Image* image : {&cpu, &gpu})
        for (vec3& p : image->pixels) p *= exposure;
    ExpectImagesClose(cpu, gpu, cpuStats, gpuStats);
}

// A demo scene played for `frames` frames twice, through the CPU frame renderer (host TLAS) and
// the CUDA one (changed records only, TLAS refit or rebuilt on the device). Every 10th frame must
// match. The TLAS is refit by default, which the runtime's policy does not do (it builds the TLAS
// afresh whenever instances moved), so that the device's refits are compared on the demos too;
// `tlasPolicy` {} plays them as the runtime does.
// Deforming meshes are deformed and refit (or rebuilt, under `blasPolicy`) on each back end.
void ExpectPlayedGpuMatchesCpu(const std::string& file, int frames,
                               BlasRebuildPolicy blasPolicy = {},
                               TlasPolicy tlasPolicy = TlasPolicy::RefitWhileGood()) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const LoadedScene loaded = LoadSceneFile(test::SourcePath("assets/scenes/" + file));
    World cpuWorld(loaded);
    World gpuWorld(loaded);
    const std::unique_ptr<FrameRenderer> cpu =
        MakeFrameRenderer(Backend::kCpu, cpuWorld.Scene(), tlasPolicy, blasPolicy);
    const std::unique_ptr<FrameRenderer> gpu =
        MakeFrameRenderer(Backend::kCuda, gpuWorld.Scene(), tlasPolicy, blasPolicy);
    RenderSettings s;
    s.width = 320;
    s.height = 180;
    s.maxDepth = loaded.scene.maxDepth;
    uint32_t rebuilds = 0, refits = 0;
    for (int f = 1; f <= frames; ++f) {
        cpuWorld.Advance(1.0f / 60.0f);
        gpuWorld.Advance(1.0f / 60.0f);
        cpu->Update(cpuWorld.Scene(), cpuWorld.Changes());
        gpu->Update(gpuWorld.Scene(), gpuWorld.Changes());
        const bool compare = f % 10 == 0;
        RenderStats cpuStats, gpuStats;
        Image cpuImage, gpuImage;
        gpu->Trace(gpuWorld.Scene(), s, compare ? &gpuImage : nullptr, &gpuStats);
        gpu->Finish();
        ASSERT_EQ(gpu->Times().frame, uint64_t(f));
        rebuilds += gpu->Times().tlasRebuilt;
        refits += !gpu->Times().tlasRebuilt && gpu->Times().uploaded > 0;
        if (!compare) continue;
        SCOPED_TRACE("frame " + std::to_string(f));
        cpu->Trace(cpuWorld.Scene(), s, &cpuImage, &cpuStats);
        ExpectImagesClose(cpuImage, gpuImage, cpuStats, gpuStats);
    }
    // The scenes move things: the device TLAS was refit, and rebuilt when spawns came; under
    // the runtime's policy it is rebuilt whenever anything moved.
    if (tlasPolicy.RebuildsChanged(gpuWorld.Scene().instances.size())) {
        EXPECT_EQ(refits, 0u);
        EXPECT_GT(rebuilds, uint32_t(frames) / 2);
    } else {
        EXPECT_GT(refits, 0u);
    }
    std::printf("%s: %u rebuilds, %u refits in %d frames\n", file.c_str(), rebuilds, refits,
                frames);
}

LoadedScene Asset(const std::string& name) {
    return LoadSceneFile(test::SourcePath("assets/scenes/" + name));
}

TEST(GpuVsCpu, DefaultScene) { ExpectGpuMatchesCpu(MakeDefaultScene()); }
TEST(GpuVsCpu, DefaultSceneNormals) { ExpectGpuMatchesCpu(MakeDefaultScene(), ViewMode::kNormals); }
TEST(GpuVsCpu, ReflectiveSphere) { ExpectGpuMatchesCpu(Asset("reflective_sphere.json").scene); }
TEST(GpuVsCpu, RefractiveSphere) { ExpectGpuMatchesCpu(Asset("refractive_sphere.json").scene); }

TEST(GpuVsCpu, TeapotShadow) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    ExpectGpuMatchesCpu(Asset("teapot_shadow.json").scene);
}

TEST(GpuVsCpu, DemoThousandInstancesPlayed) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    RTRT_REQUIRE_MODEL(dragon, "dragon_vrip_res4.ply.gz");
    ExpectPlayedGpuMatchesCpu("demo_1000_instances.json", 60);
}

TEST(GpuVsCpu, DemoPhysicsPlayed) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    ExpectPlayedGpuMatchesCpu("demo_physics.json", 90);
}

// The runtime's TLAS policy: demo_physics's 465 instances are rebuilt on both back ends whenever
// bodies moved, never refit.
TEST(GpuVsCpu, DemoPhysicsPlayedWithTheRuntimesTlasPolicy) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    ExpectPlayedGpuMatchesCpu("demo_physics.json", 40, {}, TlasPolicy{});
}

// A deforming dragon: skinned on each device, its BLAS refit every frame (and, in the second
// test, rebuilt every frame by each back end's LBVH).
TEST(GpuVsCpu, DeformingDragonPlayed) {
    RTRT_REQUIRE_MODEL(dragon, "dragon_vrip_res4.ply.gz");
    ExpectPlayedGpuMatchesCpu("demo_deforming_dragon.json", 60);
}

TEST(GpuVsCpu, DeformingDragonRebuiltEveryFrame) {
    RTRT_REQUIRE_MODEL(dragon, "dragon_vrip_res4.ply.gz");
    BlasRebuildPolicy rebuild;
    rebuild.mode = BlasRebuildPolicy::Mode::kAlwaysRebuild;
    ExpectPlayedGpuMatchesCpu("demo_deforming_dragon.json", 20, rebuild);
}

// A crowd of 1,000 skinned walkers (assets/models/walker.gltf), each in its own phase.
TEST(GpuVsCpu, DemoCrowdPlayed) { ExpectPlayedGpuMatchesCpu("demo_crowd.json", 20); }

// The frame split over several CUDA streams of one GPU (issue 17's split, RenderSettings::
// traceBands): every frame equals the unsplit one bit for bit, whatever shares the bands' measured
// times give them (frame_split_test.cpp tests the shares).
TEST(GpuFrameLoop, BandedFramesEqualWholeFrames) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const LoadedScene loaded = LoadSceneFile(test::SourcePath("assets/scenes/demo_crowd.json"));
    RenderSettings whole;
    whole.width = 320;
    whole.height = 181;  // not a multiple of the bands' granule
    whole.maxDepth = loaded.scene.maxDepth;
    RenderSettings banded = whole;
    banded.traceBands = 3;
    World wholeWorld(loaded);
    World bandedWorld(loaded);
    const std::unique_ptr<FrameRenderer> a = MakeFrameRenderer(Backend::kCuda, wholeWorld.Scene());
    const std::unique_ptr<FrameRenderer> b = MakeFrameRenderer(Backend::kCuda, bandedWorld.Scene());
    for (int f = 1; f <= 12; ++f) {
        wholeWorld.Advance(1.0f / 60.0f);
        a->Update(wholeWorld.Scene(), wholeWorld.Changes());
        bandedWorld.Advance(1.0f / 60.0f);
        b->Update(bandedWorld.Scene(), bandedWorld.Changes());
        const bool compare = f % 4 == 0;
        Image wholeImage, bandedImage;
        RenderStats wholeStats, bandedStats;
        a->Trace(wholeWorld.Scene(), whole, compare ? &wholeImage : nullptr, &wholeStats);
        b->Trace(bandedWorld.Scene(), banded, compare ? &bandedImage : nullptr, &bandedStats);
        if (!compare) continue;
        SCOPED_TRACE("frame " + std::to_string(f));
        ASSERT_EQ(wholeImage.pixels.size(), bandedImage.pixels.size());
        EXPECT_EQ(0, std::memcmp(wholeImage.pixels.data(), bandedImage.pixels.data(),
                                 wholeImage.pixels.size() * sizeof(vec3)));
        EXPECT_EQ(wholeStats.rays, bandedStats.rays);
    }
}

// Pipelined play (a game loop's overlap, `bench frame`'s pipelined pass): the host advances the
// world while earlier frames are still queued on the device. Every frame must be what one-at-a-time
// play makes of it, bit for bit: nothing the device reads may change under it.
TEST(GpuFrameLoop, PipelinedFramesEqualOneAtATime) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const LoadedScene loaded = LoadSceneFile(test::SourcePath("assets/scenes/demo_crowd.json"));
    RenderSettings s;
    s.width = 320;
    s.height = 180;
    s.maxDepth = loaded.scene.maxDepth;
    World serialWorld(loaded);
    World pipelinedWorld(loaded);
    const std::unique_ptr<FrameRenderer> serial =
        MakeFrameRenderer(Backend::kCuda, serialWorld.Scene());
    const std::unique_ptr<FrameRenderer> pipelined =
        MakeFrameRenderer(Backend::kCuda, pipelinedWorld.Scene());
    for (int f = 1; f <= 24; ++f) {
        serialWorld.Advance(1.0f / 60.0f);
        serial->Update(serialWorld.Scene(), serialWorld.Changes());
        pipelinedWorld.Advance(1.0f / 60.0f);
        pipelined->Update(pipelinedWorld.Scene(), pipelinedWorld.Changes());
        const bool compare = f % 8 == 0;  // the other frames stay queued while the host runs on
        Image a, b;
        serial->Trace(serialWorld.Scene(), s, compare ? &a : nullptr);
        serial->Finish();
        pipelined->Trace(pipelinedWorld.Scene(), s, compare ? &b : nullptr);
        if (!compare) continue;
        SCOPED_TRACE("frame " + std::to_string(f));
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(vec3)));
    }
}

TEST(GpuVsCpu, DemoGlassPlayed) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    ExpectPlayedGpuMatchesCpu("demo_glass.json", 30);
}

// glTF: base colour textures under every wrap mode, nearest and bilinear, on quads of a node
// hierarchy (assets/models/textured_quads.gltf, made by tools/make_textured_gltf.py).
TEST(GpuVsCpu, TexturedGltf) {
    const LoadedScene loaded = LoadSceneFile(test::SourcePath("assets/models/textured_quads.gltf"));
    ASSERT_NE(loaded.scene.Features() & kFeatureTextures, 0u);
    ExpectGpuMatchesCpu(loaded.scene);
}

// glTF's metallic-roughness materials (assets/models/pbr_showcase.gltf, made by
// tools/make_pbr_gltf.py): smooth to rough dielectrics and metals, every texture slot, texture
// transforms, a normal map, emission, and sun, spot and point lights in physical units.
TEST(GpuVsCpu, PbrShowcaseGltf) {
    const LoadedScene loaded = LoadSceneFile(test::SourcePath("assets/models/pbr_showcase.gltf"));
    ASSERT_NE(loaded.scene.Features() & kFeaturePbr, 0u);
    ExpectGpuMatchesCpu(loaded.scene, ViewMode::kShaded, std::exp2(loaded.output.exposureEv));
}

// The textures of KHR_materials_transmission and KHR_materials_specular (strength from the
// alpha, colour sRGB) on the device: a 2x2 texture of four different texels, bilinear, on the
// lit quad, each slot reading its own channels.
TEST(GpuVsCpu, ExtensionTexturesGltf) {
    test::GltfBuilder b = test::LitQuadScene(test::GltfBuilder::Png(
        2, 2, {255, 40, 200, 30, 20, 220, 90, 255, 128, 128, 0, 160, 60, 0, 255, 90}));
    b.doc["samplers"][0]["magFilter"] = 9729;
    b.doc["materials"][0]["extensions"] = {
        {"KHR_materials_transmission",
         {{"transmissionFactor", 0.9}, {"transmissionTexture", {{"index", 0}}}}},
        {"KHR_materials_specular",
         {{"specularTexture", {{"index", 0}}}, {"specularColorTexture", {{"index", 0}}}}}};
    const std::string path = ::testing::TempDir() + "rtrt_gpu_extension_textures.glb";
    test::GltfBuilder::Save(path, b.Glb());
    const LoadedScene loaded = LoadSceneFile(path);
    ASSERT_NE(loaded.scene.pbrMaterials.at(0).specularTexture, kNoTexture);
    ExpectGpuMatchesCpu(loaded.scene, ViewMode::kShaded, std::exp2(loaded.output.exposureEv));
}

// glTF vertex colours on the device: per-vertex colours times a bilinear base colour texture on
// the lit quad (PBR), and the same colours under the default Blinn-Phong material.
TEST(GpuVsCpu, VertexColoursGltf) {
    for (const bool pbr : {true, false}) {
        test::GltfBuilder b = test::LitQuadScene(test::GltfBuilder::Png(
            2, 2, {255, 40, 200, 255, 30, 20, 220, 255, 128, 128, 0, 255, 60, 0, 255, 255}));
        b.doc["samplers"][0]["magFilter"] = 9729;
        b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
        nlohmann::json& primitive = b.doc["meshes"][0]["primitives"][0];
        if (!pbr) primitive.erase("material");
        primitive["attributes"]["COLOR_0"] = b.Floats(
            {1, 0.2f, 0.1f, 1, 0.3f, 1, 0, 1, 0.5f, 0.5f, 1, 1, 0.9f, 0.8f, 0.1f, 1}, "VEC4", 4);
        const std::string path = ::testing::TempDir() + "rtrt_gpu_vertex_colors.glb";
        test::GltfBuilder::Save(path, b.Glb());
        const LoadedScene loaded = LoadSceneFile(path);
        ASSERT_FALSE(loaded.scene.blases.at(loaded.scene.instances.at(0).blasId)->colors.empty());
        ExpectGpuMatchesCpu(loaded.scene, ViewMode::kShaded, std::exp2(loaded.output.exposureEv));
    }
}

// The GPU samples texels exactly as the CPU does: an unlit quad filling the image shows each
// texel of a 4x4 nearest-filtered texture on 2x2 pixels, bit for bit.
TEST(GpuVsCpu, TexturedQuadTexelsDecoded) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    std::vector<uint8_t> rgb;
    for (int i = 0; i < 16; ++i)
        rgb.insert(rgb.end(), {uint8_t(16 * i), uint8_t(255 - 9 * i), uint8_t(7 * i + 3)});
    const std::string path = ::testing::TempDir() + "rtrt_gpu_quad.gltf";
    test::GltfBuilder::Save(path, test::TexturedQuadGltf(4, 4, rgb, 9728, 33071));
    const LoadedScene loaded = LoadSceneFile(path);
    RenderSettings s;
    s.width = s.height = 8;
    s.maxDepth = 1;
    const Image gpu = RenderRawCuda(loaded.scene, s), cpu = RenderRaw(loaded.scene, s);
    // A glTF file alone has linear colours: its texels arrive sRGB-decoded, the GPU's powf
    // within 1e-6 of the CPU's.
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) {
                const float texel = float(rgb[3 * ((y / 2) * 4 + x / 2) + c]) * (1.0f / 255.0f);
                EXPECT_NEAR(gpu.At(x, y)[c], SrgbDecode(texel), 1e-6f) << x << "," << y;
                EXPECT_NEAR(gpu.At(x, y)[c], cpu.At(x, y)[c], 1e-6f) << x << "," << y;
            }
}

// A scene file placing the glTF twice (one spinning), played through the GPU frame loop: the
// glTF animation, the node hierarchy and the textures on the device.
TEST(GpuVsCpu, GltfDemoPlayed) { ExpectPlayedGpuMatchesCpu("gltf_demo.json", 60); }

// The frame renderer's own tests play demo_1000_instances (skipped without a GPU or its models).
class GpuFrameRenderer : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string why;
        if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
        RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
        RTRT_REQUIRE_MODEL(dragon, "dragon_vrip_res4.ply.gz");
        loaded.emplace(LoadSceneFile(test::SourcePath("assets/scenes/demo_1000_instances.json")));
    }
    std::optional<LoadedScene> loaded;
};

// Per frame only the records the World rewrote travel, and an unchanged frame sends none.
TEST_F(GpuFrameRenderer, UploadsOnlyChangedRecords) {
    World world(*loaded);
    const std::unique_ptr<FrameRenderer> gpu = MakeFrameRenderer(Backend::kCuda, world.Scene());
    RenderSettings s;
    s.width = 64;
    s.height = 36;
    world.Advance(1.0f / 60.0f);
    gpu->Update(world.Scene(), world.Changes());
    gpu->Trace(world.Scene(), s, nullptr);
    gpu->Finish();
    // Every spawned object moves; the floor never does.
    EXPECT_EQ(gpu->Times().frame, 1u);
    EXPECT_EQ(gpu->Times().uploaded, world.Scene().instances.size() - 1);
    // Under the runtime's policy a frame that moved any instance builds its TLAS afresh.
    EXPECT_TRUE(gpu->Times().tlasRebuilt);
    // With nothing changed, nothing travels and the TLAS is left alone.
    gpu->Update(world.Scene(), SceneChanges{});
    gpu->Trace(world.Scene(), s, nullptr);
    gpu->Finish();
    EXPECT_EQ(gpu->Times().frame, 2u);
    EXPECT_EQ(gpu->Times().uploaded, 0u);
    EXPECT_FALSE(gpu->Times().tlasRebuilt);
}

// The SAH cost the device's rebuild policy sees (summed on the device in fixed-order blocks) is
// the host's for the same refit tree, one update later as the device reports it.
TEST_F(GpuFrameRenderer, SahCostFollowsTheCpuRenderers) {
    World cpuWorld(*loaded), gpuWorld(*loaded);
    const std::unique_ptr<FrameRenderer> cpu =
        MakeFrameRenderer(Backend::kCpu, cpuWorld.Scene(), TlasPolicy::RefitWhileGood());
    const std::unique_ptr<FrameRenderer> gpu =
        MakeFrameRenderer(Backend::kCuda, gpuWorld.Scene(), TlasPolicy::RefitWhileGood());
    RenderSettings s;
    s.width = 32;
    s.height = 18;
    float cpuBefore = 0.0f;
    int compared = 0;
    for (int f = 1; f <= 12; ++f) {
        cpuWorld.Advance(1.0f / 60.0f);
        gpuWorld.Advance(1.0f / 60.0f);
        cpu->Update(cpuWorld.Scene(), cpuWorld.Changes());
        gpu->Update(gpuWorld.Scene(), gpuWorld.Changes());
        cpu->Trace(cpuWorld.Scene(), s, nullptr);
        gpu->Trace(gpuWorld.Scene(), s, nullptr);
        gpu->Finish();
        // Until either rebuilds, both refit the same first tree.
        if (cpu->Times().tlasRebuilt || gpu->Times().tlasRebuilt) break;
        if (f > 1) {
            SCOPED_TRACE("frame " + std::to_string(f));
            ASSERT_GT(cpuBefore, 0.0f);
            EXPECT_NEAR(gpu->Times().tlasSahCost, cpuBefore, 1e-4f * cpuBefore);
            ++compared;
        }
        cpuBefore = cpu->Times().tlasSahCost;
    }
    EXPECT_GE(compared, 5);
}

// Both frame renderers build their first TLAS from the same records: the same LBVH, bit for bit.
TEST_F(GpuFrameRenderer, FirstTlasEqualsTheCpuRenderers) {
    World world(*loaded);
    for (int f = 0; f < 30; ++f) world.Advance(1.0f / 60.0f);
    const Tlas cpu = MakeFrameRenderer(Backend::kCpu, world.Scene())->CurrentTlas();
    const Tlas gpu = MakeFrameRenderer(Backend::kCuda, world.Scene())->CurrentTlas();
    ASSERT_EQ(TlasLeafInstances(cpu).size(), world.Scene().instances.size());
    ASSERT_EQ(cpu.nodes.size(), gpu.nodes.size());
    EXPECT_EQ(std::memcmp(cpu.nodes.data(), gpu.nodes.data(), cpu.nodes.size() * sizeof(BvhNode)),
              0);
}

// A spatial-split BLAS (triangles in several leaves, leaf boxes tighter than their triangles)
// traces on the GPU as on the CPU.
TEST(GpuVsCpu, SpatialSplitTeapot) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    const TriangleMesh mesh = TessellateTeapot(teapot, 6);
    BvhBuildOptions options;
    options.builder = BvhBuilder::kSpatialSah;
    auto blas = std::make_shared<const Blas>(BuildTriangleBlas(mesh, options));
    ASSERT_GT(blas->PrimCount(), mesh.indices.size()) << "no triangle was split";
    ExpectGpuMatchesCpu(MakePaperScene(blas));
}

TEST(GpuVsCpu, FullDragon) {
    RTRT_REQUIRE_MODEL(dragon, "dragon_vrip.ply.gz");
    ExpectGpuMatchesCpu(Asset("dragon.json").scene);
}

}  // namespace
}  // namespace rtrt
