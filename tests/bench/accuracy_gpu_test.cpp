// The accuracy benchmark's GPU path: each variant's kernel renders what the CPU renders where
// rounding cannot decide the outcome, and shows the same failure as the CPU where it does. Label
// gpu: CI has no GPU and skips these.
#include <gtest/gtest.h>

#include "bench/accuracy/accuracy_policy.h"
#include "bench/accuracy/accuracy_renderer.h"
#include "bench/accuracy/accuracy_scenes.h"
#include "bench/accuracy/image_metrics.h"

namespace rtrt {
namespace {

RenderSettings Settings(uint32_t spp) {
    RenderSettings s;
    s.width = 240;
    s.height = 135;
    s.maxDepth = 8;
    s.samplesPerPixel = spp;
    return s;
}

// Tolerance of tests/render_rt/gpu_vs_cpu_test.cpp: the GPU contracts multiply-adds and rounds
// powf/sqrtf differently, which can flip a silhouette or shadow-edge pixel.
void ExpectClose(const Image& gpu, const Image& cpu) {
    EXPECT_LE(Rmse(gpu, cpu), 1.0 / 255.0);
    EXPECT_LE(OutlierRate(gpu, cpu, 4.0f / 255.0f), 0.005);
}

TEST(AccuracyGpu, RobustVariantsMatchTheCpuWithSupersampling) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const RenderScene scene = MakeFarSpheresScene();
    // Moller-Trumbore has no triangles to differ on here; it checks that variant's kernel runs.
    for (uint32_t accuracy : {0u, uint32_t(kAccuracyMollerTrumbore)}) {
        for (uint32_t spp : {1u, 4u}) {
            SCOPED_TRACE(testing::Message() << "accuracy " << accuracy << ", " << spp << " spp");
            const RenderSettings s = Settings(spp);
            Image cpu;
            RenderAccuracyCpu(scene, s, accuracy, cpu);
            const CudaAccuracyRun gpu = RunAccuracyCuda(scene, s, accuracy, 0, 1);
            ExpectClose(gpu.image, cpu);
            EXPECT_LE(MismatchRate(gpu.objects, PrimaryObjectsCpu(scene, s, accuracy)), 0.005);
        }
    }
}

TEST(AccuracyGpu, NaiveSphereAndFixedEpsilonFailOnTheGpuToo) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    const RenderScene scene = MakeFarSpheresScene();
    const RenderSettings s = Settings(1);
    const Image reference = RenderReference(scene, s);
    const ObjectIds referenceObjects = ReferencePrimaryObjects(scene, s);
    const CudaAccuracyRun base = RunAccuracyCuda(scene, s, kAccuracyDefault, 0, 1);
    EXPECT_LE(OutlierRate(base.image, reference, 0.1f), 0.001);
    EXPECT_LE(MismatchRate(base.objects, referenceObjects), 0.001);
    // The CPU loses ~5% of primary hits and shows ~10% outliers (docs/accuracy.md).
    const CudaAccuracyRun naive = RunAccuracyCuda(scene, s, kAccuracyNaiveSphere, 0, 1);
    EXPECT_GE(MismatchRate(naive.objects, referenceObjects), 0.01);
    const CudaAccuracyRun epsilon = RunAccuracyCuda(scene, s, kAccuracyFixedEpsilon, 0, 1);
    EXPECT_GE(OutlierRate(epsilon.image, reference, 0.1f), 0.01);
}

}  // namespace
}  // namespace rtrt
