#include "engine/bvh/build/spatial_split_builder.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <vector>

#include "engine/bvh/build/prim_ref.h"
#include "engine/bvh/build/sah_bins.h"

namespace rtrt {
namespace {

// Subtrees at least this large are built as parallel tasks.
constexpr uint32_t kParallelThreshold = 4096;
// Deeper than this a node becomes a leaf whatever its size, so traversal stacks never overflow.
constexpr uint32_t kMaxDepth = kBvhStackSize - 4;
// Planes per axis of the spatial-split search.
constexpr uint32_t kSpatialBins = 32;

Aabb Intersection(const Aabb& a, const Aabb& b) {
    return {glm::max(a.min, b.min), glm::min(a.max, b.max)};
}

// The parts of a reference on either side of the plane x[axis] = plane: each the bounds of the
// triangle's points on that side (its corners and where its edges cross the plane), within the
// reference's box. An empty box means the reference has nothing on that side.
struct RefHalves {
    Aabb left, right;
};

RefHalves SplitReference(const Triangle& t, const Aabb& box, int axis, float plane) {
    const vec3 v[3] = {t.v0, t.v1, t.v2};
    RefHalves h;
    vec3 scale(0.0f);
    for (int i = 0; i < 3; ++i) {
        const vec3 a = v[i], b = v[(i + 1) % 3];
        scale = glm::max(scale, glm::abs(a));
        if (a[axis] <= plane) h.left.Grow(a);
        if (a[axis] >= plane) h.right.Grow(a);
        if ((a[axis] < plane && b[axis] > plane) || (a[axis] > plane && b[axis] < plane)) {
            const float s = (plane - a[axis]) / (b[axis] - a[axis]);
            vec3 x = a + s * (b - a);
            x[axis] = plane;
            h.left.Grow(x);
            h.right.Grow(x);
        }
    }
    // The crossing points' other coordinates are rounded: widen the halves by a few units in
    // the last place of the triangle's coordinates so that they bound the exact parts. The
    // plane itself is exact, and so is the reference's box.
    vec3 pad = scale * 1e-6f;
    pad[axis] = 0.0f;
    for (Aabb* half : {&h.left, &h.right}) {
        if (half->IsEmpty()) continue;
        *half = Intersection({half->min - pad, half->max + pad}, box);
    }
    h.left.max[axis] = std::min(h.left.max[axis], plane);
    h.right.min[axis] = std::max(h.right.min[axis], plane);
    return h;
}

struct ObjectSplit {
    SahBins::Plane plane;
    Aabb left, right;  // the children's boxes
};

struct SpatialSplit {
    int axis = -1;
    float position = 0.0f;
    float cost = kInfinity;  // sum of N * area over both sides
};

// The plane between spatial bins i - 1 and i of a node's box.
float SpatialPlane(const Aabb& box, int axis, uint32_t i) {
    return box.min[axis] + float(i) * ((box.max[axis] - box.min[axis]) / float(kSpatialBins));
}

// Extra references allowed over the whole tree: FRACTION of the triangle count, read as 0 when
// it is not a positive number and capped at 4.
uint32_t ReferenceBudget(float fraction, size_t triangles) {
    const double f = fraction > 0.0f ? std::min(double(fraction), 4.0) : 0.0;
    return uint32_t(std::min(f * double(triangles), double(UINT32_MAX / 2)));
}

class SpatialSplitBuilder {
  public:
    SpatialSplitBuilder(std::span<const Triangle> triangles, const BvhBuildOptions& options)
        : triangles_(triangles),
          options_(options),
          binCount_(std::clamp(options.binCount, 2u, kMaxSahBins)),
          budget_(ReferenceBudget(options.spatialSplitBudget, triangles.size())),
          slotCapacity_(triangles.size() + budget_),
          nodes_(new BvhNode[2 * slotCapacity_ + 2]),
          leafIds_(new uint32_t[slotCapacity_]) {}

    Bvh Run() {
        std::vector<PrimRef> refs(triangles_.size());
        for (uint32_t i = 0; i < refs.size(); ++i) refs[i] = PrimRef(triangles_[i].Bounds(), i);
        rootArea_ = BoundRefs(refs.data(), 0, uint32_t(refs.size())).Boxes().Area();
        nodeCount_ = 2;  // root, then the unused slot that aligns child pairs
        BuildNode(0, std::move(refs), budget_, 0);
        return Relayout();
    }

  private:
    void BuildNode(uint32_t nodeIndex, std::vector<PrimRef> refs, uint32_t budget, uint32_t depth) {
        const uint32_t count = uint32_t(refs.size());
        const RangeBounds range = BoundRefs(refs.data(), 0, count);
        const Aabb box = range.Boxes();
        BvhNode& node = nodes_[nodeIndex];
        node.SetBounds(box);
        if (count <= 1 || depth >= kMaxDepth) return MakeLeaf(node, refs);

        std::vector<PrimRef> left, right;
        uint32_t leftBudget = 0, rightBudget = 0;
        if (!Split(refs, range, budget, &left, &right, &leftBudget, &rightBudget))
            return MakeLeaf(node, refs);
        std::vector<PrimRef>().swap(refs);

        const uint32_t pair = nodeCount_.fetch_add(2);
        node.leftFirst = pair;
        node.primCount = 0;
        auto buildLeft = [&] { BuildNode(pair, std::move(left), leftBudget, depth + 1); };
        auto buildRight = [&] { BuildNode(pair + 1, std::move(right), rightBudget, depth + 1); };
        if (count >= kParallelThreshold) {
            tbb::parallel_invoke(buildLeft, buildRight);
        } else {
            buildLeft();
            buildRight();
        }
    }

    // Chooses between a leaf, the best object split and the best spatial split by the SAH and
    // partitions REFS; false for "make a leaf".
    bool Split(std::vector<PrimRef>& refs, const RangeBounds& range, uint32_t budget,
               std::vector<PrimRef>* left, std::vector<PrimRef>* right, uint32_t* leftBudget,
               uint32_t* rightBudget) const {
        const uint32_t count = uint32_t(refs.size());
        const bool mayBeLeaf = count <= options_.maxLeafSize;
        const Aabb box = range.Boxes();
        const float nodeArea = std::max(box.Area(), 1e-30f);
        auto splitCost = [&](float cost) {
            return kSahTraversalCost + kSahIntersectionCost * cost / nodeArea;
        };

        ObjectSplit object;
        const Aabb centroids = range.Centroids();
        const bool separable = MaxComponent(centroids.Extent()) > 0.0f;
        const BinMapping mapping(centroids, binCount_);
        if (separable) object = FindObjectSplit(refs, mapping);

        SpatialSplit spatial;
        const float overlap =
            object.plane.axis >= 0 ? Intersection(object.left, object.right).Area() : box.Area();
        if (budget > 0 && overlap > kSpatialSplitOverlap * rootArea_)
            spatial = FindSpatialSplit(refs, box);

        const float best = std::min(object.plane.cost, spatial.cost);
        if (mayBeLeaf &&
            (best == kInfinity || kSahIntersectionCost * float(count) <= splitCost(best)))
            return false;

        uint32_t duplicates = 0;
        if (spatial.cost < object.plane.cost &&
            PartitionSpatially(refs, spatial, budget, left, right, &duplicates)) {
        } else if (object.plane.axis >= 0) {
            for (const PrimRef& r : refs)
                (mapping.Bin(r, object.plane.axis) < object.plane.bin ? left : right)->push_back(r);
        } else {
            // No plane separates the references (all centroids coincide): halve the list.
            left->assign(refs.begin(), refs.begin() + count / 2);
            right->assign(refs.begin() + count / 2, refs.end());
        }
        // What is left of the budget goes to the children by their sizes.
        const uint64_t rest = budget - duplicates;
        *leftBudget = uint32_t(rest * left->size() / (left->size() + right->size()));
        *rightBudget = uint32_t(rest - *leftBudget);
        return true;
    }

    ObjectSplit FindObjectSplit(const std::vector<PrimRef>& refs, const BinMapping& mapping) const {
        SahBins bins;
        bins.Add(refs.data(), refs.data() + refs.size(), mapping);
        ObjectSplit split;
        split.plane = bins.BestPlane(mapping);
        if (split.plane.axis < 0) return split;
        for (const PrimRef& r : refs) {
            Aabb& side =
                mapping.Bin(r, split.plane.axis) < split.plane.bin ? split.left : split.right;
            side.Grow(r.Box());
        }
        return split;
    }

    // Bins every reference's parts between kSpatialBins planes per axis: a part enters the
    // first bin it touches and leaves the last, and every bin grows by the part of the
    // triangle inside it.
    SpatialSplit FindSpatialSplit(const std::vector<PrimRef>& refs, const Aabb& box) const {
        SpatialSplit best;
        for (int axis = 0; axis < 3; ++axis) {
            const float extent = box.max[axis] - box.min[axis];
            if (!(extent > 0.0f)) continue;
            Aabb bins[kSpatialBins];
            uint32_t entries[kSpatialBins] = {}, exits[kSpatialBins] = {};
            const float scale = float(kSpatialBins) / extent;
            auto binOf = [&](float x) {
                const float b = (x - box.min[axis]) * scale;
                return b >= float(kSpatialBins - 1) ? kSpatialBins - 1
                                                    : (b > 0.0f ? uint32_t(b) : 0u);
            };
            for (const PrimRef& r : refs) {
                const uint32_t first = binOf(r.lo[axis]);
                const uint32_t last = std::max(first, binOf(r.hi[axis]));
                Aabb rest = r.Box();
                for (uint32_t b = first; b < last; ++b) {
                    const RefHalves h = SplitReference(triangles_[r.id], rest, axis,
                                                       SpatialPlane(box, axis, b + 1));
                    bins[b].Grow(h.left);
                    rest = h.right;
                }
                bins[last].Grow(rest);
                ++entries[first];
                ++exits[last];
            }
            float rightCost[kSpatialBins];
            uint32_t rightCount[kSpatialBins];
            Aabb acc;
            uint32_t n = 0;
            for (uint32_t b = kSpatialBins - 1; b > 0; --b) {
                acc.Grow(bins[b]);
                n += exits[b];
                rightCost[b] = float(n) * acc.Area();
                rightCount[b] = n;
            }
            acc = Aabb();
            n = 0;
            for (uint32_t b = 1; b < kSpatialBins; ++b) {
                acc.Grow(bins[b - 1]);
                n += entries[b - 1];
                if (n == 0 || rightCount[b] == 0) continue;
                const float cost = float(n) * acc.Area() + rightCost[b];
                if (cost < best.cost) best = {axis, SpatialPlane(box, axis, b), cost};
            }
        }
        return best;
    }

    // Partitions at the spatial split's plane: references wholly on one side go there, those
    // that straddle it are split, or kept whole on one side where that costs less (the paper's
    // reference unsplitting). False, with nothing moved, when the split needs more duplicates
    // than BUDGET allows or leaves a side empty.
    bool PartitionSpatially(const std::vector<PrimRef>& refs, const SpatialSplit& split,
                            uint32_t budget, std::vector<PrimRef>* left,
                            std::vector<PrimRef>* right, uint32_t* duplicates) const {
        const int axis = split.axis;
        const float plane = split.position;
        struct Straddler {
            const PrimRef* ref;
            RefHalves halves;
        };
        std::vector<Straddler> straddlers;
        Aabb leftBox, rightBox;
        uint32_t leftCount = 0, rightCount = 0;
        for (const PrimRef& r : refs) {
            if (r.hi[axis] <= plane) {
                leftBox.Grow(r.Box());
                ++leftCount;
            } else if (r.lo[axis] >= plane) {
                rightBox.Grow(r.Box());
                ++rightCount;
            } else {
                const RefHalves h = SplitReference(triangles_[r.id], r.Box(), axis, plane);
                leftBox.Grow(h.left);
                rightBox.Grow(h.right);
                leftCount += !h.left.IsEmpty();
                rightCount += !h.right.IsEmpty();
                straddlers.push_back({&r, h});
            }
        }
        // Each straddler decided against the totals of the full split.
        const float leftArea = leftBox.Area(), rightArea = rightBox.Area();
        const float splitCost = leftArea * float(leftCount) + rightArea * float(rightCount);
        enum Side : uint8_t { kBoth, kLeft, kRight };
        std::vector<Side> sides(straddlers.size(), kBoth);
        uint32_t kept = 0;
        for (size_t i = 0; i < straddlers.size(); ++i) {
            const RefHalves& h = straddlers[i].halves;
            if (h.left.IsEmpty() || h.right.IsEmpty()) {
                sides[i] = h.left.IsEmpty() ? kRight : kLeft;
                continue;
            }
            Aabb leftWith = leftBox, rightWith = rightBox;
            leftWith.Grow(straddlers[i].ref->Box());
            rightWith.Grow(straddlers[i].ref->Box());
            const float toLeft =
                leftWith.Area() * float(leftCount) + rightArea * float(rightCount - 1);
            const float toRight =
                leftArea * float(leftCount - 1) + rightWith.Area() * float(rightCount);
            if (toLeft < splitCost && toLeft <= toRight) {
                sides[i] = kLeft;
            } else if (toRight < splitCost) {
                sides[i] = kRight;
            } else {
                ++kept;
            }
        }
        if (kept > budget) return false;

        left->reserve(leftCount);
        right->reserve(rightCount);
        size_t s = 0;
        for (const PrimRef& r : refs) {
            if (r.hi[axis] <= plane) {
                left->push_back(r);
            } else if (r.lo[axis] >= plane) {
                right->push_back(r);
            } else {
                const RefHalves& h = straddlers[s].halves;
                if (sides[s] == kLeft) left->push_back(r);
                if (sides[s] == kRight) right->push_back(r);
                if (sides[s] == kBoth) {
                    left->push_back(PrimRef(h.left, r.id));
                    right->push_back(PrimRef(h.right, r.id));
                }
                ++s;
            }
        }
        if (left->empty() || right->empty()) {
            left->clear();
            right->clear();
            return false;
        }
        *duplicates = kept;
        return true;
    }

    void MakeLeaf(BvhNode& node, const std::vector<PrimRef>& refs) {
        const uint32_t first = leafSlots_.fetch_add(uint32_t(refs.size()));
        for (size_t i = 0; i < refs.size(); ++i) leafIds_[first + i] = refs[i].id;
        node.leftFirst = first;
        node.primCount = std::max(uint32_t(refs.size()), 1u);
    }

    // Renumbers the nodes depth-first and the leaves' slots in the same order (deterministic
    // whatever order the parallel tasks took), with each child pair at even indices.
    Bvh Relayout() const {
        Bvh out;
        out.primOrder.reserve(leafSlots_.load());
        out.nodes.resize(nodeCount_.load());
        out.nodes[1] = BvhNode{vec3(0), 0, vec3(0), 0};
        uint32_t next = 2;
        struct Item {
            uint32_t oldIndex, newIndex;
        };
        std::vector<Item> stack{{0, 0}};
        while (!stack.empty()) {
            const Item item = stack.back();
            stack.pop_back();
            const BvhNode& old = nodes_[item.oldIndex];
            BvhNode& node = out.nodes[item.newIndex];
            node = old;
            if (old.IsLeaf()) {
                node.leftFirst = uint32_t(out.primOrder.size());
                out.primOrder.insert(out.primOrder.end(), leafIds_.get() + old.leftFirst,
                                     leafIds_.get() + old.leftFirst + old.primCount);
                continue;
            }
            node.leftFirst = next;
            next += 2;
            stack.push_back({old.leftFirst + 1, node.leftFirst + 1});
            stack.push_back({old.leftFirst, node.leftFirst});
        }
        out.nodes.resize(next);
        return out;
    }

    std::span<const Triangle> triangles_;
    BvhBuildOptions options_;
    uint32_t binCount_;
    uint32_t budget_;
    size_t slotCapacity_;
    float rootArea_ = 0.0f;
    std::unique_ptr<BvhNode[]> nodes_;
    std::unique_ptr<uint32_t[]> leafIds_;
    std::atomic<uint32_t> nodeCount_{0};
    std::atomic<uint32_t> leafSlots_{0};
};

}  // namespace

Bvh BuildSpatialSplitBvh(std::span<const Triangle> triangles, const BvhBuildOptions& options) {
    if (triangles.empty()) {
        BvhBuildOptions binned = options;
        binned.builder = BvhBuilder::kBinnedSah;
        return BuildBvh({}, binned);
    }
    return SpatialSplitBuilder(triangles, options).Run();
}

}  // namespace rtrt
