#pragma once
// Top-level acceleration structure over instances: a binned SAH build (best trees, for static
// scenes) or the LBVH (fast, rebuilt every frame in the runtime).
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

enum class TlasBuilder { kSah, kLbvh };

// World bounds of every instance (its BLAS bounds under its transform).
std::vector<Aabb> InstanceWorldBounds(std::span<const Instance> instances,
                                      std::span<const Aabb> blasBounds);

Tlas BuildTlas(std::span<const Instance> instances, std::span<const Aabb> blasBounds,
               TlasBuilder builder = TlasBuilder::kSah);

}  // namespace rtrt
