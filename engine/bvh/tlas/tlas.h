#pragma once
// Top-level acceleration structure over instances: a binned SAH build (best trees, for static
// scenes) or the LBVH (fast, rebuilt every frame in the runtime). Every leaf holds one instance
// and names it itself (leftFirst is the instance's index), so a TLAS keeps no leaf order. (The
// traversals would take a leaf of several instances as [leftFirst, leftFirst + primCount).)
#include <span>
#include <vector>

#include "engine/bvh/blas/blas.h"
#include "engine/bvh/tlas/instance.h"

namespace rtrt {

struct Tlas {
    AlignedVector<BvhNode> nodes;  // leaves: leftFirst = instance index, primCount = 1
};

// World bounds of a box under an affine transform (the 8 transformed corners' bounds).
RT_HD inline Aabb TransformBounds(const Affine& m, const Aabb& b) {
    Aabb out;
    if (b.IsEmpty()) return out;
    for (int corner = 0; corner < 8; ++corner) {
        const vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                     (corner & 4) ? b.max.z : b.min.z);
        out.Grow(m.Point(p));
    }
    return out;
}

// The instances' world boxes as a TLAS build reads them (the Boxes of lbvh_steps.h): computed
// from the record and its BLAS's box each time, so that no array of them is kept.
struct InstanceWorldBoxes {
    const Instance* instances;
    const Aabb* blasBounds;  // by BLAS id
    RT_HD Aabb operator[](size_t i) const {
        const Instance& inst = instances[i];
        return TransformBounds(inst.ObjectToWorld(), blasBounds[inst.blasId]);
    }
};

enum class TlasBuilder { kSah, kLbvh };

// World bounds of every instance (its BLAS bounds under its transform).
std::vector<Aabb> InstanceWorldBounds(std::span<const Instance> instances,
                                      std::span<const Aabb> blasBounds);

// The instances its leaves name, in node order (each once, for a well-formed TLAS).
std::vector<uint32_t> TlasLeafInstances(const Tlas& tlas);

Tlas BuildTlas(std::span<const Instance> instances, std::span<const Aabb> blasBounds,
               TlasBuilder builder = TlasBuilder::kSah);

}  // namespace rtrt
