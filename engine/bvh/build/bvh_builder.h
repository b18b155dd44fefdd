#pragma once
// Builders of binary BVHs over primitive bounding boxes; the same code builds a BLAS over
// triangles or spheres and the simple CPU TLAS over instances.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/bvh/layout/bvh_node.h"

namespace rtrt {

enum class BvhBuilder {
    kBinnedSah,      // default: SAH evaluated at binCount planes per axis (Wald 2007)
    kSweepSah,       // SAH evaluated between every pair of sorted centroids, per axis
    kCentroidSplit,  // the original paper's builder: split at the middle of the centroid bounds
    kSpatialSah,     // binned SAH plus spatial splits (SBVH) for triangles; binned for other boxes
};

std::string_view BuilderName(BvhBuilder builder);
// Parses "binned", "sweep", "centroid" or "sbvh"; false for anything else.
bool ParseBuilder(std::string_view name, BvhBuilder* builder);

struct BvhBuildOptions {
    BvhBuilder builder = BvhBuilder::kBinnedSah;
    uint32_t maxLeafSize =
        8;  // leaves hold at most this many primitives (unless the depth cap hits)
    uint32_t binCount = 32;
    // kSpatialSah: at most this many extra triangle references per triangle. A .rtmodel's key
    // does not hold it: change it only with kRtModelRevision.
    float spatialSplitBudget = 0.25f;
};

// SAH cost constants: one unit per node traversal and per primitive test.
inline constexpr float kSahTraversalCost = 1.0f;
inline constexpr float kSahIntersectionCost = 1.0f;

struct Bvh {
    AlignedVector<BvhNode> nodes;     // depth-first order, root at 0, index 1 unused
    std::vector<uint32_t> primOrder;  // slot i of the leaves holds input primitive primOrder[i]
};

// kSpatialSah needs the triangles (BuildSpatialSplitBvh); over bare boxes it builds binned SAH.
Bvh BuildBvh(std::span<const Aabb> primBounds, const BvhBuildOptions& options = {});

// SAH cost of a tree, relative to its root's area: sum over interior nodes of Ct A(n)/A(root)
// plus sum over leaves of Ci N(n) A(n)/A(root).
float SahCost(std::span<const BvhNode> nodes);

// Recomputes every node's bounds bottom-up from the primitives' bounds, given in slot order
// (slotBounds[i] bounds the primitive in leaf slot i). The topology stays.
void Refit(std::span<BvhNode> nodes, std::span<const Aabb> slotBounds);

struct BvhStats {
    uint32_t nodeCount = 0;  // reachable nodes
    uint32_t leafCount = 0;
    uint32_t maxDepth = 0;
    uint32_t minLeafSize = 0;
    uint32_t maxLeafSize = 0;
    double meanLeafSize = 0.0;
    std::vector<uint32_t> leafSizeHistogram;  // [n]: leaves holding n primitives
    float sahCost = 0.0f;
    size_t bytes = 0;  // node array size in memory
};
BvhStats ComputeStats(std::span<const BvhNode> nodes);

}  // namespace rtrt
