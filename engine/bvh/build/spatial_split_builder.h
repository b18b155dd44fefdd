#pragma once
// Spatial-split BVH over triangles (SBVH: Stich, Friedrich and Dietrich 2009, "Spatial Splits in
// Bounding Volume Hierarchies"). Besides the binned object split it tries splitting space at
// binned planes where the object split's children would overlap: a triangle that straddles the
// plane is then referenced from both sides, each reference bounded by the part of the triangle
// on its side. Leaves get tighter boxes at the price of some triangles in more than one leaf.
#include <span>

#include "engine/bvh/build/bvh_builder.h"
#include "engine/geometry/primitives.h"

namespace rtrt {

// Spatial splits are tried only where the object split's children overlap by more than this
// fraction of the root's surface area (the paper's alpha), so that large, well-separated nodes
// are not binned twice.
inline constexpr float kSpatialSplitOverlap = 1e-5f;

// The tree's primOrder may name a triangle more than once (once per leaf it is in): its size is
// the number of leaf slots, at most (1 + options.spatialSplitBudget) times the triangle count.
// The budget is shared out among subtrees by their reference counts, so the tree is the same
// on any number of threads.
Bvh BuildSpatialSplitBvh(std::span<const Triangle> triangles, const BvhBuildOptions& options = {});

}  // namespace rtrt
