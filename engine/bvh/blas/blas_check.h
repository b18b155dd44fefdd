#pragma once
// Validation of a BLAS that comes from outside (an .rtmodel file): everything the tracer relies
// on without checking, so that a hostile file gives an error instead of undefined behaviour.
#include <string>

#include "engine/bvh/blas/blas.h"

namespace rtrt {

// Deepest tree the traversal stacks hold (the builders stop at the same depth).
inline constexpr uint32_t kMaxBvhDepth = kBvhStackSize - 4;

// Throws InputError(file, field, reason) unless: array sizes agree with the kind (primIds and
// the primitives, normals, uvs and colours absent or one per triangle, nodes4 only for
// triangles); there is at least one primitive; every binary and 4-wide node is reached exactly
// once from the root through forward child links, no deeper than kMaxBvhDepth, with finite
// non-inverted boxes (or, for unused 4-wide slots, the empty box); leaf ranges lie inside the
// primitives; primIds is a permutation, or with REPEATED_IDS for triangles (a spatial-split
// tree, whose triangles may be in several leaves) the ids 0 to some n - 1, each at least once;
// vertices, uvs and spheres are finite (radii >= 0).
void CheckBlas(const Blas& blas, const std::string& file, bool repeatedIds = false);

}  // namespace rtrt
