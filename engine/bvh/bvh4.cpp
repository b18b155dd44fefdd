#include "engine/bvh/bvh4.h"

#include <algorithm>
#include <vector>

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
        nodes_.emplace_back();
        const BvhNode& root = binary_[0];
        if (root.Bounds().IsEmpty()) {
            for (int i = 0; i < 4; ++i) SetChild(nodes_[0], i, Aabb(), 0, 0);  // hits nothing
        } else if (root.IsLeaf()) {
            Fill(0, {0});
        } else {
            Fill(0, {root.leftFirst, root.leftFirst + 1});
        }
        return std::move(nodes_);
    }

  private:
    // Fills wide node `index` from binary nodes `open`, opening the largest interior one until
    // there are four.
    void Fill(uint32_t index, std::vector<uint32_t> open) {
        while (open.size() < 4) {
            int best = -1;
            float bestArea = -1.0f;
            for (size_t i = 0; i < open.size(); ++i) {
                const BvhNode& n = binary_[open[i]];
                if (!n.IsLeaf() && n.Bounds().Area() > bestArea) {
                    bestArea = n.Bounds().Area();
                    best = int(i);
                }
            }
            if (best < 0) break;
            const uint32_t left = binary_[open[best]].leftFirst;
            open[best] = left;
            open.push_back(left + 1);
        }
        Bvh4Node node;
        for (int i = 0; i < 4; ++i) SetChild(node, i, Aabb(), 0, 0);
        std::vector<std::pair<int, uint32_t>> interior;
        for (size_t i = 0; i < open.size(); ++i) {
            const BvhNode& n = binary_[open[i]];
            if (n.IsLeaf()) {
                SetChild(node, int(i), n.Bounds(), n.leftFirst, n.primCount);
            } else {
                const uint32_t wide = uint32_t(nodes_.size());
                nodes_.emplace_back();
                SetChild(node, int(i), n.Bounds(), wide, 0);
                interior.push_back({int(i), open[i]});
            }
        }
        nodes_[index] = node;
        for (const auto& [slot, binaryIndex] : interior) {
            const BvhNode& n = binary_[binaryIndex];
            Fill(nodes_[index].child[slot], {n.leftFirst, n.leftFirst + 1});
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
