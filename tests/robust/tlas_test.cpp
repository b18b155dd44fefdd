// TLAS hard cases on the CPU (tlas_checks.h), and refit quality over many frames.
#include "engine/bvh/tlas/dynamic_tlas.h"
#include "tests/robust/cpu_runner.h"
#include "tests/robust/tlas_checks.h"

namespace rtrt::robust {
namespace {

TEST(TlasHardCases, AllAtOnePointFarOutlierEqualMortonCodes) {
    CheckTlasDegenerateInputs(CpuRunner{});
}

// 512 boxes wander for 1000 frames under the refit policy at any size (dynamic_tlas.h: refit
// until the SAH cost exceeds 1.25 x the cost at the last rebuild). Expected: after every update the
// cost is within that bound; the policy does rebuild (motion degrades refits) and does refit (the
// rebuilds are fewer than half the frames); every 100 frames the refit tree still traces exactly
// what brute force finds.
TEST(TlasHardCases, RefitQualityDriftIsBoundedAndTriggersRebuilds) {
    RenderScene scene;
    scene.AddMaterial({});
    const uint32_t box = AddMeshBlas(scene, SubdividedBox(1, vec3(-0.4f), vec3(0.4f)).mesh);
    std::vector<vec3> positions;
    for (int i = 0; i < 512; ++i) {
        positions.push_back(1.5f * vec3(i % 8, (i / 8) % 8, i / 64));
        scene.AddInstance(box, 0, Placement(positions.back()));
    }
    const std::vector<Aabb> blasBounds{scene.blases[0]->bounds};
    DynamicTlas tlas(TlasPolicy::RefitWhileGood());
    uint32_t rebuilds = 0;
    float worstGrowth = 0.0f;
    for (uint32_t frame = 0; frame < 1000; ++frame) {
        for (size_t i = 0; i < positions.size(); ++i) {
            const float phase = 0.37f * float(i) + 0.02f * float(frame);
            positions[i] +=
                0.05f * vec3(std::sin(phase), std::cos(1.3f * phase), std::sin(0.7f * phase));
            const glm::mat4 m = Placement(positions[i]);
            SetTransform(scene.instances[i], m);
        }
        const TlasUpdateStats stats = tlas.Update(scene.instances, blasBounds, false);
        rebuilds += stats.rebuilt;
        worstGrowth = std::max(worstGrowth, stats.sahCost / stats.rebuiltSahCost);
        ASSERT_LE(stats.sahCost, 1.25f * stats.rebuiltSahCost) << "frame " << frame;
        if (frame % 100 != 99) continue;
        scene.SetTlas(Tlas{tlas.Tree().nodes});
        const std::vector<Ray> rays = RaysAtInstances(scene, vec3(6), 10.0f, 2000, frame);
        SCOPED_TRACE("frame " + std::to_string(frame));
        ExpectSameAsBruteForce(rays, CpuRunner{}.Scene(scene, rays));
    }
    EXPECT_GE(rebuilds, 2u);
    EXPECT_LT(rebuilds, 500u);
    RecordProperty("rebuilds", int(rebuilds));
    RecordProperty("worst_sah_growth_percent", int(100.0f * (worstGrowth - 1.0f)));
}

}  // namespace
}  // namespace rtrt::robust
