#pragma once
// Top-level acceleration structure over instances: a binned SAH build (best trees, for static
// scenes) or the LBVH (fast, rebuilt every frame in the runtime). Every leaf holds one instance
// and names it itself (leftFirst is the instance's index), so a TLAS keeps no leaf order. (The
// traversals would take a leaf of several instances as [leftFirst, leftFirst + primCount).)
#include <memory>
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

// The sphere a BLAS of one sphere is (w: its radius), else w = 0 (BlasSpheres).
vec4 BlasSphere(const Blas& blas);

// An instance's world box: its BLAS's box under its transform, and for a BLAS of one sphere also
// the box of that sphere's image, an ellipsoid whose box is exact (half extent r |row i of L| on
// axis i), where the turned cube's corners reach up to sqrt(3) r from the centre: a rolling ball
// took up to 5x the volume it needs in the TLAS. The two boxes are intersected; the ellipsoid's is
// widened by a few ulps for the rounding of its centre and extents.
RT_HD inline Aabb InstanceWorldBox(const Instance& inst, const Aabb& blasBox, vec4 blasSphere) {
    const Affine m = inst.ObjectToWorld();
    Aabb box = TransformBounds(m, blasBox);
    if (!(blasSphere.w > 0.0f) || box.IsEmpty()) return box;
    const vec3 centre = m.Point(vec3(blasSphere));
    const float reach = blasSphere.w + glm::length(vec3(blasSphere));
    for (int i = 0; i < 3; ++i) {
        const float rowLength = glm::length(vec3(m.row[i]));
        const float half = blasSphere.w * rowLength;
        const float error = fabsf(centre[i]) + fabsf(m.row[i].w) + rowLength * reach;
#if defined(__CUDA_ARCH__)
        const float slack = __fmul_rn(Gamma(5), error);  // not fused into the sums below
#else
        const float slack = Gamma(5) * error;
#endif
        box.min[i] = fmaxf(box.min[i], centre[i] - half - slack);
        box.max[i] = fminf(box.max[i], centre[i] + half + slack);
    }
    return box;
}

// The instances' world boxes as a TLAS build reads them (the Boxes of lbvh_steps.h): computed
// from the record and its BLAS's box each time, so that no array of them is kept.
struct InstanceWorldBoxes {
    const Instance* instances;
    const Aabb* blasBounds;   // by BLAS id
    const vec4* blasSpheres;  // by BLAS id (BlasSphere), or null: boxes only
    RT_HD Aabb operator[](size_t i) const {
        const Instance& inst = instances[i];
        return InstanceWorldBox(inst, blasBounds[inst.blasId],
                                blasSpheres ? blasSpheres[inst.blasId] : vec4(0.0f));
    }
};

enum class TlasBuilder { kSah, kLbvh };

// BlasSphere of every BLAS.
std::vector<vec4> BlasSpheres(std::span<const std::shared_ptr<const Blas>> blases);

// World bounds of every instance (InstanceWorldBox; blasSpheres empty: the boxes alone).
std::vector<Aabb> InstanceWorldBounds(std::span<const Instance> instances,
                                      std::span<const Aabb> blasBounds,
                                      std::span<const vec4> blasSpheres = {});

// The instances its leaves name, in node order (each once, for a well-formed TLAS).
std::vector<uint32_t> TlasLeafInstances(const Tlas& tlas);

Tlas BuildTlas(std::span<const Instance> instances, std::span<const Aabb> blasBounds,
               TlasBuilder builder = TlasBuilder::kSah, std::span<const vec4> blasSpheres = {});

}  // namespace rtrt
