// The slab test's hard cases on the CPU (slab_checks.h), and the IsTraceable gate in front of it.
#include <cmath>
#include <random>

#include "tests/robust/cpu_runner.h"
#include "tests/robust/slab_checks.h"

namespace rtrt::robust {
namespace {

TEST(SlabTest, ZeroComponentsFacesFlatBoxesAndNanLanes) { CheckSlabCases(CpuRunner{}); }

// Expected: NaN or infinite components, a NaN tMax or a zero direction make a ray untraceable;
// large finite values do not (their sum would overflow, the gate must not compute it).
TEST(SlabTest, NanAndInfiniteRaysAreNotTraceable) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), kInfinity, vec3(nan, 0, 1), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(kInfinity, 0, 0), kInfinity, vec3(0, 0, 1), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), kInfinity, vec3(0), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), kInfinity, vec3(-0.0f), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), nan, vec3(0, 0, 1), 0}));
    EXPECT_TRUE(IsTraceable(Ray{vec3(0), kInfinity, vec3(0, 0, 1), 0}));
    EXPECT_TRUE(IsTraceable(Ray{vec3(3e38f), kInfinity, vec3(3e38f, 3e38f, 1), 0}));
}

// The GPU's fused form may enter more boxes (its widened planes; axis-parallel rays, whose
// inf - inf planes it drops), never fewer: on random boxes and rays, near and far from the
// origin, every box SlabTest enters it enters too, and it agrees on most.
TEST(SlabTest, FusedFormEntersEveryBoxTheReferenceEnters) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), size(0.0f, 1.0f);
    uint32_t entered = 0, extra = 0;
    const int kCases = 400000;
    for (int i = 0; i < kCases; ++i) {
        const float scale = std::pow(10.0f, float(i % 9) - 2.0f);  // 1e-2 .. 1e6
        const vec3 centre = vec3(unit(rng), unit(rng), unit(rng)) * scale;
        const vec3 half = vec3(size(rng), size(rng), size(rng)) * (0.05f * scale);
        const vec3 origin = centre + vec3(unit(rng), unit(rng), unit(rng)) * (0.3f * scale);
        vec3 dir = centre - origin + vec3(unit(rng), unit(rng), unit(rng)) * half;
        if (i % 7 == 0) dir = vec3(unit(rng), unit(rng), unit(rng));  // mostly misses
        const Ray ray{origin, i % 5 == 0 ? size(rng) * scale : kInfinity, dir, 0};
        const RaySetup r = MakeBoxRaySetup(ray);
        float t0, t1;
        const bool reference = SlabTest(centre - half, centre + half, r, ray.tMax, &t0);
        const bool fused = SlabTestFused(centre - half, centre + half, r, ray.tMax, &t1);
        entered += reference;
        extra += fused && !reference;
        if (reference && !fused)
            ADD_FAILURE() << "case " << i << ": the fused test misses a box the reference enters";
    }
    EXPECT_GT(entered, uint32_t(kCases / 4));
    EXPECT_LT(extra, uint32_t(kCases / 1000)) << "the fused test enters too many boxes";
}

}  // namespace
}  // namespace rtrt::robust
