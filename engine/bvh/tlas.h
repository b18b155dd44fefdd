#pragma once
// Top-level acceleration structure over instances. This is the simple CPU build (binned SAH over
// instance world bounds); the per-frame LBVH replaces it in the runtime.
#include <span>
#include <vector>

#include "engine/bvh/blas.h"
#include "engine/bvh/instance.h"

namespace rtrt {

struct Tlas {
    AlignedVector<BvhNode> nodes;
    std::vector<uint32_t> instanceOrder;
};

// World bounds of a box under an affine transform (the 8 transformed corners' bounds).
Aabb TransformBounds(const Affine& m, const Aabb& b);

Tlas BuildTlas(std::span<const Instance> instances, std::span<const Aabb> blasBounds);

}  // namespace rtrt
