#include "engine/bvh/bvh_builder.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>
#include <numeric>

namespace rtrt {
namespace {

// Subtrees at least this large are built as parallel tasks.
constexpr uint32_t kParallelThreshold = 4096;
// Deeper than this a node becomes a leaf whatever its size, so traversal stacks never overflow.
constexpr uint32_t kMaxDepth = kBvhStackSize - 4;

struct Split {
    int axis = -1;
    float position = 0.0f;    // centroid coordinate; binned and centroid splits
    uint32_t sweepIndex = 0;  // sweep: first primitive of the right side, in sorted order
    float cost = kInfinity;
};

class Builder {
  public:
    Builder(std::span<const Aabb> bounds, const BvhBuildOptions& options)
        : bounds_(bounds), options_(options), centroids_(bounds.size()), order_(bounds.size()) {
        for (size_t i = 0; i < bounds.size(); ++i) centroids_[i] = bounds[i].Centroid();
        std::iota(order_.begin(), order_.end(), 0u);
        nodes_.resize(std::max<size_t>(2 * bounds.size() + 2, 2));
    }

    Bvh Run() {
        nodeCount_ = 2;  // root, then the unused slot that aligns child pairs
        BuildNode(0, 0, uint32_t(bounds_.size()), 0);
        return Relayout();
    }

  private:
    Aabb RangeBounds(uint32_t begin, uint32_t end, Aabb* centroidBounds) const {
        Aabb b, c;
        for (uint32_t i = begin; i < end; ++i) {
            b.Grow(bounds_[order_[i]]);
            c.Grow(centroids_[order_[i]]);
        }
        *centroidBounds = c;
        return b;
    }

    void BuildNode(uint32_t nodeIndex, uint32_t begin, uint32_t end, uint32_t depth) {
        Aabb centroidBounds;
        const Aabb nodeBounds = RangeBounds(begin, end, &centroidBounds);
        BvhNode& node = nodes_[nodeIndex];
        node.SetBounds(nodeBounds);
        const uint32_t count = end - begin;
        const float leafCost = kSahIntersectionCost * float(count);
        if (count <= 1 || depth >= kMaxDepth) return MakeLeaf(node, begin, count);

        uint32_t mid = FindAndPartition(begin, end, nodeBounds, centroidBounds, leafCost);
        if (mid == begin || mid == end) return MakeLeaf(node, begin, count);

        const uint32_t left = nodeCount_.fetch_add(2);
        node.leftFirst = left;
        node.primCount = 0;
        if (count >= kParallelThreshold) {
            tbb::parallel_invoke([&] { BuildNode(left, begin, mid, depth + 1); },
                                 [&] { BuildNode(left + 1, mid, end, depth + 1); });
        } else {
            BuildNode(left, begin, mid, depth + 1);
            BuildNode(left + 1, mid, end, depth + 1);
        }
    }

    void MakeLeaf(BvhNode& node, uint32_t begin, uint32_t count) {
        node.leftFirst = begin;
        node.primCount = std::max(count, 1u);
    }

    // Returns where the partitioned range splits; begin or end for "make a leaf".
    uint32_t FindAndPartition(uint32_t begin, uint32_t end, const Aabb& nodeBounds,
                              const Aabb& centroidBounds, float leafCost) {
        const uint32_t count = end - begin;
        const bool mayBeLeaf = count <= options_.maxLeafSize;
        const float nodeArea = nodeBounds.Area();
        if (MaxComponent(centroidBounds.Extent()) <= 0.0f) {
            // All centroids coincide: no plane separates them, so halve the list.
            return mayBeLeaf ? begin : begin + count / 2;
        }
        if (options_.builder == BvhBuilder::kCentroidSplit) {
            if (mayBeLeaf) return begin;
            return CentroidSplit(begin, end, centroidBounds);
        }
        Split split = options_.builder == BvhBuilder::kSweepSah
                          ? FindSweepSplit(begin, end)
                          : FindBinnedSplit(begin, end, centroidBounds);
        // split.cost is sum N*A over both sides; normalise to this node's area.
        const float splitCost =
            kSahTraversalCost + kSahIntersectionCost * split.cost / std::max(nodeArea, 1e-30f);
        if (split.axis < 0 || (mayBeLeaf && leafCost <= splitCost)) {
            return mayBeLeaf ? begin : begin + count / 2;
        }
        if (options_.builder == BvhBuilder::kSweepSah) return begin + split.sweepIndex;
        return Partition(begin, end, split.axis, split.position, centroidBounds);
    }

    uint32_t Partition(uint32_t begin, uint32_t end, int axis, float position,
                       const Aabb& centroidBounds) {
        auto* first = order_.data() + begin;
        auto* last = order_.data() + end;
        auto* mid = std::partition(first, last, [&](uint32_t p) {
            return BinOf(centroids_[p][axis], centroidBounds, axis) < position;
        });
        return uint32_t(mid - order_.data());
    }

    // Binned SAH: bins are compared by index so partitioning agrees exactly with binning.
    float BinOf(float c, const Aabb& centroidBounds, int axis) const {
        const float lo = centroidBounds.min[axis];
        const float scale = float(options_.binCount) / (centroidBounds.max[axis] - lo);
        return float(std::min(options_.binCount - 1, uint32_t((c - lo) * scale)));
    }

    Split FindBinnedSplit(uint32_t begin, uint32_t end, const Aabb& centroidBounds) const {
        constexpr uint32_t kMaxBins = 64;
        const uint32_t binCount = std::min(options_.binCount, kMaxBins);
        Split best;
        for (int axis = 0; axis < 3; ++axis) {
            if (centroidBounds.max[axis] <= centroidBounds.min[axis]) continue;
            Aabb binBounds[kMaxBins];
            uint32_t binCounts[kMaxBins] = {};
            for (uint32_t i = begin; i < end; ++i) {
                const uint32_t p = order_[i];
                const uint32_t bin = uint32_t(BinOf(centroids_[p][axis], centroidBounds, axis));
                binBounds[bin].Grow(bounds_[p]);
                ++binCounts[bin];
            }
            float rightCost[kMaxBins];
            Aabb acc;
            uint32_t n = 0;
            for (uint32_t b = binCount - 1; b > 0; --b) {
                acc.Grow(binBounds[b]);
                n += binCounts[b];
                rightCost[b] = float(n) * acc.Area();
            }
            acc = Aabb();
            n = 0;
            for (uint32_t b = 0; b + 1 < binCount; ++b) {
                acc.Grow(binBounds[b]);
                n += binCounts[b];
                const float cost = float(n) * acc.Area() + rightCost[b + 1];
                if (n > 0 && n < end - begin && cost < best.cost) {
                    best.axis = axis;
                    best.position = float(b + 1);
                    best.cost = cost;
                }
            }
        }
        return best;
    }

    // Full sweep: sort along each axis and evaluate every split; the winning axis's order stays.
    Split FindSweepSplit(uint32_t begin, uint32_t end) {
        const uint32_t count = end - begin;
        Split best;
        std::vector<uint32_t> sorted[3];
        std::vector<float> rightCost(count);
        for (int axis = 0; axis < 3; ++axis) {
            sorted[axis].assign(order_.begin() + begin, order_.begin() + end);
            std::sort(sorted[axis].begin(), sorted[axis].end(), [&](uint32_t a, uint32_t b) {
                const float ca = centroids_[a][axis], cb = centroids_[b][axis];
                return ca < cb || (ca == cb && a < b);
            });
            Aabb acc;
            for (uint32_t i = count - 1; i > 0; --i) {
                acc.Grow(bounds_[sorted[axis][i]]);
                rightCost[i] = float(count - i) * acc.Area();
            }
            acc = Aabb();
            for (uint32_t i = 1; i < count; ++i) {
                acc.Grow(bounds_[sorted[axis][i - 1]]);
                const float cost = float(i) * acc.Area() + rightCost[i];
                if (cost < best.cost) {
                    best.axis = axis;
                    best.sweepIndex = i;
                    best.cost = cost;
                }
            }
        }
        if (best.axis >= 0)
            std::copy(sorted[best.axis].begin(), sorted[best.axis].end(), order_.begin() + begin);
        return best;
    }

    uint32_t CentroidSplit(uint32_t begin, uint32_t end, const Aabb& centroidBounds) {
        const int axis = MaxDimension(centroidBounds.Extent());
        const float middle = centroidBounds.Centroid()[axis];
        auto* mid = std::partition(order_.data() + begin, order_.data() + end,
                                   [&](uint32_t p) { return centroids_[p][axis] < middle; });
        uint32_t split = uint32_t(mid - order_.data());
        if (split == begin || split == end) split = begin + (end - begin) / 2;
        return split;
    }

    // Renumbers the nodes depth-first (deterministic whatever order the parallel tasks took)
    // and puts each child pair at even indices.
    Bvh Relayout() {
        Bvh out;
        out.primOrder = std::move(order_);
        out.nodes.resize(std::max<uint32_t>(nodeCount_.load(), 2));
        out.nodes[0] = nodes_[0];
        out.nodes[1] = BvhNode{vec3(0), 0, vec3(0), 0};
        uint32_t next = 2;
        struct Item {
            uint32_t oldIndex, newIndex;
        };
        std::vector<Item> stack{{0, 0}};
        while (!stack.empty()) {
            Item item = stack.back();
            stack.pop_back();
            const BvhNode& old = nodes_[item.oldIndex];
            out.nodes[item.newIndex] = old;
            if (old.IsLeaf()) continue;
            const uint32_t pair = next;
            next += 2;
            out.nodes[item.newIndex].leftFirst = pair;
            stack.push_back({old.leftFirst + 1, pair + 1});
            stack.push_back({old.leftFirst, pair});
        }
        out.nodes.resize(next);
        return out;
    }

    std::span<const Aabb> bounds_;
    BvhBuildOptions options_;
    std::vector<vec3> centroids_;
    std::vector<uint32_t> order_;
    std::vector<BvhNode> nodes_;
    std::atomic<uint32_t> nodeCount_{0};
};

void AccumulateStats(std::span<const BvhNode> nodes, uint32_t index, uint32_t depth, float rootArea,
                     BvhStats* stats, uint64_t* leafPrims) {
    const BvhNode& node = nodes[index];
    ++stats->nodeCount;
    stats->maxDepth = std::max(stats->maxDepth, depth);
    const float relArea = rootArea > 0.0f ? node.Bounds().Area() / rootArea : 1.0f;
    if (node.IsLeaf()) {
        ++stats->leafCount;
        stats->maxLeafSize = std::max(stats->maxLeafSize, node.primCount);
        *leafPrims += node.primCount;
        stats->sahCost += kSahIntersectionCost * float(node.primCount) * relArea;
        return;
    }
    stats->sahCost += kSahTraversalCost * relArea;
    AccumulateStats(nodes, node.leftFirst, depth + 1, rootArea, stats, leafPrims);
    AccumulateStats(nodes, node.leftFirst + 1, depth + 1, rootArea, stats, leafPrims);
}

}  // namespace

std::string_view BuilderName(BvhBuilder builder) {
    switch (builder) {
        case BvhBuilder::kBinnedSah:
            return "binned";
        case BvhBuilder::kSweepSah:
            return "sweep";
        case BvhBuilder::kCentroidSplit:
            return "centroid";
    }
    return "unknown";
}

bool ParseBuilder(std::string_view name, BvhBuilder* builder) {
    for (BvhBuilder b :
         {BvhBuilder::kBinnedSah, BvhBuilder::kSweepSah, BvhBuilder::kCentroidSplit}) {
        if (name == BuilderName(b)) {
            *builder = b;
            return true;
        }
    }
    return false;
}

Bvh BuildBvh(std::span<const Aabb> primBounds, const BvhBuildOptions& options) {
    if (primBounds.empty()) {
        // An empty tree: a root leaf with no primitives and an empty box that no ray enters.
        Bvh empty;
        empty.nodes.resize(2, BvhNode{vec3(kInfinity), 0, vec3(-kInfinity), 0});
        return empty;
    }
    return Builder(primBounds, options).Run();
}

float SahCost(std::span<const BvhNode> nodes) { return ComputeStats(nodes).sahCost; }

BvhStats ComputeStats(std::span<const BvhNode> nodes) {
    BvhStats stats;
    if (nodes.empty() || (nodes[0].IsLeaf() && nodes[0].Bounds().IsEmpty())) return stats;
    uint64_t leafPrims = 0;
    AccumulateStats(nodes, 0, 0, nodes[0].Bounds().Area(), &stats, &leafPrims);
    stats.meanLeafSize = stats.leafCount ? double(leafPrims) / stats.leafCount : 0.0;
    stats.bytes = nodes.size_bytes();
    return stats;
}

void Refit(std::span<BvhNode> nodes, std::span<const Aabb> slotBounds) {
    // Depth-first layout puts children after their parent, so a reverse sweep is bottom-up.
    for (size_t i = nodes.size(); i-- > 0;) {
        BvhNode& node = nodes[i];
        if (i == 1) continue;
        Aabb b;
        if (node.IsLeaf()) {
            for (uint32_t k = 0; k < node.primCount && node.leftFirst + k < slotBounds.size(); ++k)
                b.Grow(slotBounds[node.leftFirst + k]);
        } else {
            b.Grow(nodes[node.leftFirst].Bounds());
            b.Grow(nodes[node.leftFirst + 1].Bounds());
        }
        node.SetBounds(b);
    }
}

}  // namespace rtrt
