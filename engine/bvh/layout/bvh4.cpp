#include "engine/bvh/layout/bvh4.h"

#include <algorithm>

namespace rtrt {
namespace {

void SetChild(Bvh4Node& node, int i, const Aabb& b, uint32_t child, uint32_t count) {
    node.minX[i] = b.min.x;
    node.minY[i] = b.min.y;
    node.minZ[i] = b.min.z;
    node.maxX[i] = b.max.x;
    node.maxY[i] = b.max.y;
    node.maxZ[i] = b.max.z;
    node.child[i] = child;
    node.count[i] = count;
}

class Collapser {
  public:
    explicit Collapser(std::span<const BvhNode> binary) : binary_(binary) {}

    AlignedVector<Bvh4Node> Run() {
        // Each wide node stands for at least one binary interior node, of which there are at
        // most half the array: reserving that spares the copies of a growing array.
        nodes_.reserve(binary_.size() / 2 + 1);
        nodes_.emplace_back();
        const BvhNode& root = binary_[0];
        if (root.Bounds().IsEmpty()) {
            for (int i = 0; i < 4; ++i) SetChild(nodes_[0], i, Aabb(), 0, 0);  // hits nothing
        } else if (root.IsLeaf()) {
            Fill(0, Open{{0}, 1});
        } else {
            Fill(0, Open{{root.leftFirst, root.leftFirst + 1}, 2});
        }
        return std::move(nodes_);
    }

  private:
    // Up to four binary nodes that become one wide node's children (no heap allocation: this
    // runs once per wide node).
    struct Open {
        uint32_t node[4];
        int count;
    };

    // Fills wide node `index` from binary nodes `open`, opening the largest interior one until
    // there are four.
    void Fill(uint32_t index, Open open) {
        while (open.count < 4) {
            int best = -1;
            float bestArea = -1.0f;
            for (int i = 0; i < open.count; ++i) {
                const BvhNode& n = binary_[open.node[i]];
                if (!n.IsLeaf() && n.Bounds().Area() > bestArea) {
                    bestArea = n.Bounds().Area();
                    best = i;
                }
            }
            if (best < 0) break;
            const uint32_t left = binary_[open.node[best]].leftFirst;
            open.node[best] = left;
            open.node[open.count++] = left + 1;
        }
        Bvh4Node node;
        for (int i = 0; i < 4; ++i) SetChild(node, i, Aabb(), 0, 0);
        int interiorSlots[4], interiorCount = 0;
        for (int i = 0; i < open.count; ++i) {
            const BvhNode& n = binary_[open.node[i]];
            if (n.IsLeaf()) {
                SetChild(node, i, n.Bounds(), n.leftFirst, n.primCount);
            } else {
                const uint32_t wide = uint32_t(nodes_.size());
                nodes_.emplace_back();
                SetChild(node, i, n.Bounds(), wide, 0);
                interiorSlots[interiorCount++] = i;
            }
        }
        nodes_[index] = node;
        for (int k = 0; k < interiorCount; ++k) {
            const int slot = interiorSlots[k];
            const BvhNode& n = binary_[open.node[slot]];
            Fill(nodes_[index].child[slot], Open{{n.leftFirst, n.leftFirst + 1}, 2});
        }
    }

    std::span<const BvhNode> binary_;
    AlignedVector<Bvh4Node> nodes_;
};

}  // namespace

AlignedVector<Bvh4Node> CollapseToBvh4(std::span<const BvhNode> binary) {
    return Collapser(binary).Run();
}

}  // namespace rtrt
