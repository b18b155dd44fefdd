// The TLAS's SAH cost summed on the GPU (cuda/tlas_sah_cost.h) equals the sum of the same node
// terms on the host to float rounding, repeats to the bit (the rebuild policy's decisions depend
// on it), and keeps the cost of the last fresh build apart from the last cost. Label gpu.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "engine/bvh/build/sah_term.h"
#include "engine/render_rt/cuda/tlas_sah_cost.h"
#include "engine/render_rt/renderer.h"

namespace rtrt {
namespace {

// Nodes of random boxes inside the unit root box, half of them leaves of one instance.
std::vector<BvhNode> RandomTree(uint32_t leafCount, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<BvhNode> nodes(leafCount == 0 ? 2u : 2u * leafCount);
    for (BvhNode& node : nodes) {
        const vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        node.SetBounds({glm::min(a, b), glm::max(a, b)});
        node.leftFirst = 0;
        node.primCount = u(rng) < 0.5f ? 1u : 0u;
    }
    nodes[0].SetBounds({vec3(0.0f), vec3(1.0f)});
    nodes[0].primCount = leafCount == 1 ? 1u : 0u;
    return nodes;
}

TEST(TlasSahCost, SumsTheNodeTermsOnTheGpu) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    std::mt19937 rng(7);
    TlasSahCost cost;
    // Sizes across the block sums' levels (2,048 values per block: one level up to 1,024
    // instances, two up to 2,097,152, three above).
    for (uint32_t n : {0u, 1u, 2u, 5u, 1000u, 1024u, 2049u, 100000u, 1000000u, 2100000u}) {
        SCOPED_TRACE("instances " + std::to_string(n));
        const std::vector<BvhNode> nodes = RandomTree(n, rng);
        double expected = 0.0;
        for (uint32_t i = 0; i < nodes.size(); ++i) expected += SahNodeTerm(nodes.data(), i);
        const DeviceBuffer<BvhNode> device{std::span<const BvhNode>(nodes)};
        cost.Queue(device.Data(), n, true);
        cost.Collect();
        const float rebuilt = cost.Last();
        EXPECT_NEAR(rebuilt, expected, 1e-5 * std::max(1.0, expected));
        EXPECT_EQ(cost.Rebuilt(), rebuilt);
        cost.Queue(device.Data(), n, false);
        cost.Collect();
        EXPECT_EQ(cost.Last(), rebuilt) << "the same sum, to the bit";
        // A refit's cost leaves the fresh build's alone.
        std::vector<BvhNode> grown = nodes;
        for (size_t i = 2; i < grown.size(); ++i) grown[i].SetBounds({vec3(0.0f), vec3(1.0f)});
        const DeviceBuffer<BvhNode> refit{std::span<const BvhNode>(grown)};
        cost.Queue(refit.Data(), n, false);
        cost.Collect();
        EXPECT_EQ(cost.Rebuilt(), rebuilt);
        if (n >= 2) {
            EXPECT_GT(cost.Last(), rebuilt);
        }
    }
}

}  // namespace
}  // namespace rtrt
