#include "engine/bvh/layout/wide_bvh.h"

#include <algorithm>
#include <cmath>

namespace rtrt {
namespace {

// Exponents stay where 2^e and 255 * 2^e are normal floats.
constexpr int kMinExponent = -120, kMaxExponent = 120;

bool IsFinite(const Aabb& b) {
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(b.min[a]) || !std::isfinite(b.max[a])) return false;
    return true;
}

// Smallest positions whose planes enclose [lo, hi] on one axis, or false when 8 bits do not
// reach at this scale.
bool QuantiseSpan(float origin, float scale, float lo, float hi, uint8_t* qlo, uint8_t* qhi) {
    double low = std::floor((double(lo) - origin) / scale);
    double high = std::ceil((double(hi) - origin) / scale);
    int l = int(std::clamp(low, 0.0, 255.0));
    int h = int(std::clamp(high, 0.0, 256.0));
    while (l > 0 && WidePlane(origin, scale, uint32_t(l)) > lo) --l;
    while (h <= 255 && WidePlane(origin, scale, uint32_t(h)) < hi) ++h;
    if (h > 255) return false;
    *qlo = uint8_t(l);
    *qhi = uint8_t(h);
    return true;
}

class WideCollapser {
  public:
    explicit WideCollapser(std::span<const BvhNode> binary) : binary_(binary) {}

    WideBvh Run() {
        if (binary_.empty()) return {};
        wide_.nodes.reserve(binary_.size() / 4 + 1);
        wide_.nodes.emplace_back();
        const BvhNode& root = binary_[0];
        Open open{{}, 0};
        if (!root.Bounds().IsEmpty()) {
            if (root.IsLeaf()) {
                open.node[open.count++] = 0;
            } else {
                open.node[open.count++] = root.leftFirst;
                open.node[open.count++] = root.leftFirst + 1;
            }
        }
        work_.push_back({0, open});
        while (!work_.empty()) {
            const Work w = work_.back();
            work_.pop_back();
            if (!Fill(w.index, w.open)) return {};
        }
        return std::move(wide_);
    }

  private:
    // Up to eight binary nodes that become one wide node's children.
    struct Open {
        uint32_t node[kWideArity];
        int count;
    };
    struct Work {
        uint32_t index;
        Open open;
    };

    // Opens the largest interior child until there are eight; children with empty boxes (nothing
    // below them can be hit) are dropped.
    Open Widen(Open open) const {
        Open kept{{}, 0};
        for (int i = 0; i < open.count; ++i)
            if (!binary_[open.node[i]].Bounds().IsEmpty()) kept.node[kept.count++] = open.node[i];
        while (kept.count < kWideArity) {
            int best = -1;
            float bestArea = -1.0f;
            for (int i = 0; i < kept.count; ++i) {
                const BvhNode& n = binary_[kept.node[i]];
                if (!n.IsLeaf() && n.Bounds().Area() > bestArea) {
                    bestArea = n.Bounds().Area();
                    best = i;
                }
            }
            if (best < 0) break;
            const uint32_t left = binary_[kept.node[best]].leftFirst;
            kept.node[best] = kept.node[--kept.count];
            for (uint32_t child : {left, left + 1})
                if (!binary_[child].Bounds().IsEmpty()) kept.node[kept.count++] = child;
        }
        return kept;
    }

    // Slot of each child: greedily the (child, slot) pair whose centre offset points most along
    // the slot's direction, so that the octant order visits near children first.
    static void AssignSlots(const Open& open, const Aabb* boxes, const Aabb& all, int* slotOf) {
        const vec3 centre = all.Centroid();
        float cost[kWideArity][kWideArity];
        for (int i = 0; i < open.count; ++i) {
            const vec3 offset = boxes[i].Centroid() - centre;
            for (int s = 0; s < kWideArity; ++s)
                cost[i][s] = ((s & 1) ? offset.x : -offset.x) + ((s & 2) ? offset.y : -offset.y) +
                             ((s & 4) ? offset.z : -offset.z);
        }
        bool childDone[kWideArity] = {}, slotUsed[kWideArity] = {};
        for (int round = 0; round < open.count; ++round) {
            int bestChild = -1, bestSlot = -1;
            for (int i = 0; i < open.count; ++i) {
                if (childDone[i]) continue;
                for (int s = 0; s < kWideArity; ++s)
                    if (!slotUsed[s] && (bestChild < 0 || cost[i][s] > cost[bestChild][bestSlot])) {
                        bestChild = i;
                        bestSlot = s;
                    }
            }
            childDone[bestChild] = slotUsed[bestSlot] = true;
            slotOf[bestChild] = bestSlot;
        }
    }

    bool Fill(uint32_t index, Open open) {
        open = Widen(open);
        WideBvhNode node{};
        if (open.count == 0) {
            wide_.nodes[index] = node;  // hits nothing
            return true;
        }
        Aabb boxes[kWideArity];
        Aabb all;
        for (int i = 0; i < open.count; ++i) {
            boxes[i] = binary_[open.node[i]].Bounds();
            if (!IsFinite(boxes[i])) return false;
            all.Grow(boxes[i]);
        }
        int slotOf[kWideArity];
        AssignSlots(open, boxes, all, slotOf);
        int childAt[kWideArity];
        std::fill(childAt, childAt + kWideArity, -1);
        for (int i = 0; i < open.count; ++i) childAt[slotOf[i]] = i;

        node.origin = all.min;
        for (int a = 0; a < 3; ++a) {
            const double extent = double(all.max[a]) - double(all.min[a]);
            int e = extent > 0.0 ? int(std::ceil(std::log2(extent / 255.0))) : kMinExponent;
            for (e = std::clamp(e, kMinExponent, kMaxExponent);; ++e) {
                if (e > kMaxExponent) return false;
                const float scale = WideScale(e);
                bool fits = true;
                for (int s = 0; s < kWideArity && fits; ++s)
                    if (childAt[s] >= 0)
                        fits = QuantiseSpan(all.min[a], scale, boxes[childAt[s]].min[a],
                                            boxes[childAt[s]].max[a], &node.qlo[a][s],
                                            &node.qhi[a][s]);
                if (fits) break;
            }
            node.exponent[a] = int8_t(e);
        }

        node.childBase = uint32_t(wide_.nodes.size());
        node.leafBase = uint32_t(wide_.leaves.size());
        for (int s = 0; s < kWideArity; ++s) {
            if (childAt[s] < 0) continue;
            const uint32_t b = open.node[childAt[s]];
            const BvhNode& n = binary_[b];
            if (n.IsLeaf()) {
                node.leafMask |= uint8_t(1u << s);
                wide_.leaves.push_back({n.leftFirst, n.primCount});
            } else {
                node.interiorMask |= uint8_t(1u << s);
                const uint32_t child = uint32_t(wide_.nodes.size());
                wide_.nodes.emplace_back();
                work_.push_back({child, Open{{n.leftFirst, n.leftFirst + 1}, 2}});
            }
        }
        wide_.nodes[index] = node;
        return true;
    }

    std::span<const BvhNode> binary_;
    WideBvh wide_;
    std::vector<Work> work_;
};

}  // namespace

WideBvh CollapseToWideBvh(std::span<const BvhNode> binary) { return WideCollapser(binary).Run(); }

}  // namespace rtrt
