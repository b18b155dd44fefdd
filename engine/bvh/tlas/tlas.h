#pragma once
// Top-level acceleration structure over instances: a binned SAH build (best trees, for static
// scenes) or the LBVH (fast, rebuilt every frame in the runtime). Every leaf holds one instance
// and names it itself (leftFirst is the instance's index), so a TLAS keeps no leaf order. (The
// traversals would take a leaf of several instances as [leftFirst, leftFirst + primCount).)
#include <memory>
#include <span>
#include <vector>

#include "engine/bvh/blas/blas.h"
#include "engine/bvh/tlas/blas_outline.h"
#include "engine/bvh/tlas/instance.h"

namespace rtrt {

struct Tlas {
    AlignedVector<BvhNode> nodes;  // leaves: leftFirst = instance index, primCount = 1
};

// d rounded to a float no greater (no less, with up = true) than d.
RT_HD inline float FloatOutward(double d, bool up) {
    const float f = float(d);
    if (up) return double(f) < d ? NextFloatUp(f) : f;
    return double(f) > d ? NextFloatDown(f) : f;
}

// The box of a sphere (xyz centre, w radius, in the instance's object space) under the
// instance's transform: an ellipsoid, whose box is exact with half extent r |row i of L| on axis
// i. L is inverted in double from the stored L^-1, the matrix the traversal applies, so that its
// rounding (which grows with the ratio of the largest to the smallest scale) stays far below a
// float's, and the box is rounded outward. A singular or non-finite transform gives NaN or
// infinite planes, which InstanceWorldBox ignores.
RT_HD inline Aabb SphereImageBox(const Instance& inst, vec4 sphere) {
    const glm::dvec3 a(inst.InverseRow(0)), b(inst.InverseRow(1)), d(inst.InverseRow(2));
    // Row i of L is (c0[i], c1[i], c2[i]) / det: the rows' pairwise cross products as columns.
    const glm::dvec3 c0 = glm::cross(b, d), c1 = glm::cross(d, a), c2 = glm::cross(a, b);
    const double inverseDet = 1.0 / glm::dot(a, c0);
    const glm::dvec3 centre(sphere), position(inst.Position());
    Aabb box;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 row = glm::dvec3(c0[i], c1[i], c2[i]) * inverseDet;
        const double middle = glm::dot(row, centre) + position[i];
        const double half = double(sphere.w) * glm::length(row);
        // Double's own rounding here, many orders below a float ulp of the result.
        const double slack = 1e-12 * (fabs(middle) + fabs(position[i]) + half);
        box.min[i] = FloatOutward(middle - half - slack, false);
        box.max[i] = FloatOutward(middle + half + slack, true);
    }
    return box;
}

// No plane infinite or NaN (either fails the comparison with the largest float).
RT_HD inline bool IsFiniteBox(const Aabb& b) {
    constexpr float kLargest = 3.40282347e38f;
    for (int i = 0; i < 3; ++i)
        if (!(fabsf(b.min[i]) <= kLargest) || !(fabsf(b.max[i]) <= kLargest)) return false;
    return true;
}

// An instance's world box: the union of its BLAS's parts' images (PartsImageBox), else its
// BLAS's box under its transform (a transform too large for the parts' rounding bound falls back
// to the box too), and for a BLAS of one sphere also the sphere's box (SphereImageBox), where
// the turned cube's corners reach up to sqrt(3) r from the centre: a rolling ball took up to 5x
// the volume it needs in the TLAS. The two boxes are intersected (fmaxf and fminf keep the
// first box's plane where the other is NaN). outline: the BLAS's, or null for the box alone.
RT_HD inline Aabb InstanceWorldBox(const Instance& inst, const Aabb& blasBox,
                                   const BlasOutline* outline) {
    const Affine m = inst.ObjectToWorld();
    Aabb box;
    if (outline && outline->partCount > 0 && !blasBox.IsEmpty())
        box = PartsImageBox(m, *outline, blasBox);
    if (!IsFiniteBox(box)) box = TransformBounds(m, blasBox);
    if (!outline || !(outline->sphere.w > 0.0f) || box.IsEmpty()) return box;
    const Aabb sphereBox = SphereImageBox(inst, outline->sphere);
    for (int i = 0; i < 3; ++i) {
        box.min[i] = fmaxf(box.min[i], sphereBox.min[i]);
        box.max[i] = fminf(box.max[i], sphereBox.max[i]);
    }
    return box;
}

// The instances' world boxes as a TLAS build reads them (the Boxes of lbvh_steps.h): computed
// from the record and its BLAS's box and outline each time, so that no array of them is kept.
struct InstanceWorldBoxes {
    const Instance* instances;
    const Aabb* blasBounds;           // by BLAS id
    const BlasOutline* blasOutlines;  // by BLAS id, or null: boxes only
    RT_HD Aabb operator[](size_t i) const {
        const Instance& inst = instances[i];
        return InstanceWorldBox(inst, blasBounds[inst.blasId],
                                blasOutlines ? &blasOutlines[inst.blasId] : nullptr);
    }
};

enum class TlasBuilder { kSah, kLbvh };

// World bounds of every instance (InstanceWorldBox; blasOutlines empty: the boxes alone).
std::vector<Aabb> InstanceWorldBounds(std::span<const Instance> instances,
                                      std::span<const Aabb> blasBounds,
                                      std::span<const BlasOutline> blasOutlines = {});

// The instances its leaves name, in node order (each once, for a well-formed TLAS).
std::vector<uint32_t> TlasLeafInstances(const Tlas& tlas);

Tlas BuildTlas(std::span<const Instance> instances, std::span<const Aabb> blasBounds,
               TlasBuilder builder = TlasBuilder::kSah,
               std::span<const BlasOutline> blasOutlines = {});

}  // namespace rtrt
