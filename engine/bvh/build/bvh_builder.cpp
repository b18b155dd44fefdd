#include "engine/bvh/build/bvh_builder.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <memory>

#include "engine/bvh/build/prim_ref.h"
#include "engine/bvh/build/sah_bins.h"

namespace rtrt {
namespace {

// Subtrees at least this large are built as parallel tasks.
constexpr uint32_t kParallelThreshold = 4096;
// Ranges at least this large are binned and bounded by parallel reductions (the top of the tree,
// where there are fewer subtrees than threads).
constexpr uint32_t kParallelScanThreshold = 65536;
// Deeper than this a node becomes a leaf whatever its size, so traversal stacks never overflow.
constexpr uint32_t kMaxDepth = kBvhStackSize - 4;

struct Split {
    int axis = -1;
    uint32_t bin = 0;         // binned: first bin of the right side
    uint32_t sweepIndex = 0;  // sweep: first primitive of the right side, in sorted order
    float cost = kInfinity;
};

class Builder {
  public:
    Builder(std::span<const Aabb> bounds, const BvhBuildOptions& options)
        : options_(options),
          binCount_(std::clamp(options.binCount, 2u, kMaxSahBins)),
          refs_(bounds.size()),
          nodeCapacity_(std::max<size_t>(2 * bounds.size() + 2, 2)),
          // Default-initialised: only the nodes the build writes are ever touched.
          nodes_(new BvhNode[nodeCapacity_]) {
        ParallelRange(0, uint32_t(bounds.size()), [&](uint32_t begin, uint32_t end) {
            for (uint32_t i = begin; i < end; ++i) refs_[i] = PrimRef(bounds[i], i);
        });
    }

    Bvh Run() {
        nodeCount_ = 2;  // root, then the unused slot that aligns child pairs
        BuildNode(0, 0, uint32_t(refs_.size()), 0);
        return Relayout();
    }

  private:
    template <typename Body>
    static void ParallelRange(uint32_t begin, uint32_t end, const Body& body) {
        tbb::parallel_for(tbb::blocked_range<uint32_t>(begin, end, 16384),
                          [&](const tbb::blocked_range<uint32_t>& r) { body(r.begin(), r.end()); });
    }

    RangeBounds BoundsOf(uint32_t begin, uint32_t end) const {
        if (end - begin < kParallelScanThreshold) return BoundRefs(refs_.data(), begin, end);
        // Min and max are exact, so the reduction order cannot change the result.
        return tbb::parallel_deterministic_reduce(
            tbb::blocked_range<uint32_t>(begin, end, 16384), RangeBounds(),
            [&](const tbb::blocked_range<uint32_t>& r, RangeBounds acc) {
                acc.Grow(BoundRefs(refs_.data(), r.begin(), r.end()));
                return acc;
            },
            [](RangeBounds a, const RangeBounds& b) {
                a.Grow(b);
                return a;
            });
    }

    void BuildNode(uint32_t nodeIndex, uint32_t begin, uint32_t end, uint32_t depth) {
        const RangeBounds range = BoundsOf(begin, end);
        BvhNode& node = nodes_[nodeIndex];
        node.SetBounds(range.Boxes());
        const uint32_t count = end - begin;
        const float leafCost = kSahIntersectionCost * float(count);
        if (count <= 1 || depth >= kMaxDepth) return MakeLeaf(node, begin, count);

        const uint32_t mid = FindAndPartition(begin, end, range, leafCost);
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
    uint32_t FindAndPartition(uint32_t begin, uint32_t end, const RangeBounds& range,
                              float leafCost) {
        const uint32_t count = end - begin;
        const bool mayBeLeaf = count <= options_.maxLeafSize;
        const Aabb centroidBounds = range.Centroids();
        const float nodeArea = range.Boxes().Area();
        if (MaxComponent(centroidBounds.Extent()) <= 0.0f) {
            // All centroids coincide: no plane separates them, so halve the list.
            return mayBeLeaf ? begin : begin + count / 2;
        }
        if (options_.builder == BvhBuilder::kCentroidSplit) {
            if (mayBeLeaf) return begin;
            return CentroidSplit(begin, end, centroidBounds);
        }
        const BinMapping mapping(centroidBounds, binCount_);
        Split split = options_.builder == BvhBuilder::kSweepSah
                          ? FindSweepSplit(begin, end)
                          : FindBinnedSplit(begin, end, mapping);
        // split.cost is sum N*A over both sides; normalise to this node's area.
        const float splitCost =
            kSahTraversalCost + kSahIntersectionCost * split.cost / std::max(nodeArea, 1e-30f);
        if (split.axis < 0 || (mayBeLeaf && leafCost <= splitCost)) {
            return mayBeLeaf ? begin : begin + count / 2;
        }
        if (options_.builder == BvhBuilder::kSweepSah) return begin + split.sweepIndex;
        PrimRef* first = refs_.data() + begin;
        PrimRef* mid = std::partition(first, refs_.data() + end, [&](const PrimRef& r) {
            return mapping.Bin(r, split.axis) < split.bin;
        });
        return uint32_t(mid - refs_.data());
    }

    // Binned SAH (Wald 2007): one pass bins every axis at once; bins are compared by index so
    // partitioning agrees exactly with binning.
    Split FindBinnedSplit(uint32_t begin, uint32_t end, const BinMapping& mapping) const {
        SahBins bins;
        if (end - begin < kParallelScanThreshold) {
            bins.Add(refs_.data() + begin, refs_.data() + end, mapping);
        } else {
            // Bin boxes are unions and counts are sums: exact, so the result is deterministic.
            bins = tbb::parallel_deterministic_reduce(
                tbb::blocked_range<uint32_t>(begin, end, 16384), bins,
                [&](const tbb::blocked_range<uint32_t>& r, SahBins acc) {
                    acc.Add(refs_.data() + r.begin(), refs_.data() + r.end(), mapping);
                    return acc;
                },
                [](SahBins a, const SahBins& b) {
                    a.Merge(b);
                    return a;
                });
        }
        const SahBins::Plane plane = bins.BestPlane(mapping);
        Split best;
        best.axis = plane.axis;
        best.bin = plane.bin;
        best.cost = plane.cost;
        return best;
    }

    // Full sweep: sort along each axis and evaluate every split; the winning axis's order stays.
    Split FindSweepSplit(uint32_t begin, uint32_t end) {
        const uint32_t count = end - begin;
        Split best;
        std::vector<PrimRef> sorted[3];
        std::vector<float> rightCost(count);
        for (int axis = 0; axis < 3; ++axis) {
            sorted[axis].assign(refs_.begin() + begin, refs_.begin() + end);
            std::sort(sorted[axis].begin(), sorted[axis].end(),
                      [&](const PrimRef& a, const PrimRef& b) {
                          const float ca = a.Centroid(axis), cb = b.Centroid(axis);
                          return ca < cb || (ca == cb && a.id < b.id);
                      });
            Aabb acc;
            for (uint32_t i = count - 1; i > 0; --i) {
                acc.Grow(sorted[axis][i].Box());
                rightCost[i] = float(count - i) * acc.Area();
            }
            acc = Aabb();
            for (uint32_t i = 1; i < count; ++i) {
                acc.Grow(sorted[axis][i - 1].Box());
                const float cost = float(i) * acc.Area() + rightCost[i];
                if (cost < best.cost) {
                    best.axis = axis;
                    best.sweepIndex = i;
                    best.cost = cost;
                }
            }
        }
        if (best.axis >= 0)
            std::copy(sorted[best.axis].begin(), sorted[best.axis].end(), refs_.begin() + begin);
        return best;
    }

    uint32_t CentroidSplit(uint32_t begin, uint32_t end, const Aabb& centroidBounds) {
        const int axis = MaxDimension(centroidBounds.Extent());
        const float middle = centroidBounds.Centroid()[axis];
        PrimRef* mid = std::partition(refs_.data() + begin, refs_.data() + end,
                                      [&](const PrimRef& r) { return r.Centroid(axis) < middle; });
        uint32_t split = uint32_t(mid - refs_.data());
        if (split == begin || split == end) split = begin + (end - begin) / 2;
        return split;
    }

    // Renumbers the nodes depth-first (deterministic whatever order the parallel tasks took)
    // and puts each child pair at even indices.
    Bvh Relayout() {
        Bvh out;
        out.primOrder.resize(refs_.size());
        ParallelRange(0, uint32_t(refs_.size()), [&](uint32_t begin, uint32_t end) {
            for (uint32_t i = begin; i < end; ++i) out.primOrder[i] = refs_[i].id;
        });
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

    BvhBuildOptions options_;
    uint32_t binCount_;
    AlignedVector<PrimRef> refs_;
    size_t nodeCapacity_;
    std::unique_ptr<BvhNode[]> nodes_;
    std::atomic<uint32_t> nodeCount_{0};
};

// A box's surface area in double: in float, a box of side 1e20 has an infinite area, and the cost's
// ratios of such areas were NaN.
double AreaInDouble(const Aabb& box) {
    if (box.IsEmpty()) return 0.0;
    const glm::dvec3 e = glm::dvec3(box.max) - glm::dvec3(box.min);
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

void AccumulateStats(std::span<const BvhNode> nodes, uint32_t index, uint32_t depth,
                     double rootArea, BvhStats* stats, uint64_t* leafPrims, double* sahCost) {
    const BvhNode& node = nodes[index];
    ++stats->nodeCount;
    stats->maxDepth = std::max(stats->maxDepth, depth);
    const double relArea = rootArea > 0.0 ? AreaInDouble(node.Bounds()) / rootArea : 1.0;
    if (node.IsLeaf()) {
        ++stats->leafCount;
        stats->minLeafSize = std::min(stats->minLeafSize, node.primCount);
        stats->maxLeafSize = std::max(stats->maxLeafSize, node.primCount);
        if (node.primCount >= stats->leafSizeHistogram.size())
            stats->leafSizeHistogram.resize(node.primCount + 1, 0);
        ++stats->leafSizeHistogram[node.primCount];
        *leafPrims += node.primCount;
        *sahCost += double(kSahIntersectionCost) * node.primCount * relArea;
        return;
    }
    *sahCost += double(kSahTraversalCost) * relArea;
    AccumulateStats(nodes, node.leftFirst, depth + 1, rootArea, stats, leafPrims, sahCost);
    AccumulateStats(nodes, node.leftFirst + 1, depth + 1, rootArea, stats, leafPrims, sahCost);
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
        case BvhBuilder::kSpatialSah:
            return "sbvh";
    }
    return "unknown";
}

bool ParseBuilder(std::string_view name, BvhBuilder* builder) {
    for (BvhBuilder b : {BvhBuilder::kBinnedSah, BvhBuilder::kSweepSah, BvhBuilder::kCentroidSplit,
                         BvhBuilder::kSpatialSah}) {
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
    // An empty root, a builder's empty leaf or the LBVH's empty pair (an interior node whose
    // children are itself and the unused position), holds nothing.
    if (nodes.empty() || nodes[0].Bounds().IsEmpty()) return stats;
    uint64_t leafPrims = 0;
    // Summed in double: a million nodes' terms in float lose the sum's third digit.
    double sahCost = 0.0;
    stats.minLeafSize = UINT32_MAX;
    AccumulateStats(nodes, 0, 0, AreaInDouble(nodes[0].Bounds()), &stats, &leafPrims, &sahCost);
    stats.sahCost = float(sahCost);
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
