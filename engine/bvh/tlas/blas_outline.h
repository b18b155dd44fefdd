#pragma once
// What bounds an instance of a BLAS more tightly than the BLAS's box under the instance's
// transform. A turned box's corners reach far beyond what it holds (a dragon turned about one
// axis took on average a third more surface area than the box of its turned vertices), and every
// ray that enters an instance's box pays for the transform and the BLAS's first nodes. So a TLAS
// bounds an instance by the union of the images of a few boxes cut from near the root of its
// BLAS's tree (the parts), each of which holds its primitives as tightly as the tree does, and
// by the sphere of a BLAS of one sphere (tlas.h: SphereImageBox).
#include <memory>
#include <span>
#include <vector>

#include "engine/bvh/blas/blas.h"
#include "engine/core/affine.h"
#include "engine/core/float_bounds.h"

namespace rtrt {

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

// The sphere a BLAS of one sphere is (w: its radius), else w = 0 (BlasOutline::sphere).
vec4 BlasSphere(const Blas& blas);

struct BlasOutline {
    static constexpr uint32_t kMaxParts = 8;
    vec4 sphere{0.0f};       // a BLAS of one sphere: xyz centre, w radius; else w = 0
    uint32_t partCount = 0;  // 0: the BLAS's box alone bounds it
    // Each part's box as centre +- half, the half extents rounded up so that the box holds the
    // node's box exactly.
    vec3 partCentre[kMaxParts];
    vec3 partHalf[kMaxParts];
};

// The outline of a BLAS as built: its sphere, and as parts the up to kMaxParts nodes reached by
// splitting, from the root down, the node of largest surface area among them until there are
// kMaxParts or only leaves (none where the root is a leaf), kept where their images under turns
// about a spread of axes take at least 3% less surface area than the turned box's. A BLAS whose
// tree will be refit or rebuilt (a deformation's slot) keeps no parts, which its new box would not
// match.
BlasOutline OutlineOfBlas(const Blas& blas, bool deforms = false);

// OutlineOfBlas of each BLAS, none of them deforming.
std::vector<BlasOutline> BlasOutlines(std::span<const std::shared_ptr<const Blas>> blases);

namespace outline_detail {
// Rounded as written on the device too (no fused multiply-add), so that host and device compute
// the same boxes where the transform's products are exact.
RT_HD inline float Mul(float a, float b) {
#if defined(__CUDA_ARCH__)
    return __fmul_rn(a, b);
#else
    return a * b;
#endif
}
RT_HD inline float Add(float a, float b) {
#if defined(__CUDA_ARCH__)
    return __fadd_rn(a, b);
#else
    return a + b;
#endif
}
}  // namespace outline_detail

// The world box of an instance placed by m (its objectToWorld) of a BLAS with box blasBox and
// parts: the union of the parts' images, rounded outward so that it holds every point
// m.Point(p) computes for p in a part. Per axis i a part's image is its centre's image +-
// |row i of m| . half; m.Point's rounding and this one's are each below gamma(3) times
// |row i| . (the largest |p| in the box) + |translation|, and the box grows by gamma(12) times it.
RT_HD inline Aabb PartsImageBox(const Affine& m, const BlasOutline& outline, const Aabb& blasBox) {
    using outline_detail::Add;
    using outline_detail::Mul;
    const vec3 reach = glm::max(glm::abs(blasBox.min), glm::abs(blasBox.max));
    Aabb box;
    for (int i = 0; i < 3; ++i) {
        const vec3 row(m.row[i]);
        const vec3 size = glm::abs(row);
        const float translation = m.row[i].w;
        const float rounding =
            Mul(Gamma(12),
                Add(Add(Add(Mul(size.x, reach.x), Mul(size.y, reach.y)), Mul(size.z, reach.z)),
                    fabsf(translation)));
        float lo = kInfinity, hi = -kInfinity;
        for (uint32_t k = 0; k < outline.partCount; ++k) {
            const vec3 c = outline.partCentre[k], h = outline.partHalf[k];
            const float centre =
                Add(Add(Add(Mul(row.x, c.x), Mul(row.y, c.y)), Mul(row.z, c.z)), translation);
            const float half =
                Add(Add(Add(Mul(size.x, h.x), Mul(size.y, h.y)), Mul(size.z, h.z)), rounding);
            lo = fminf(lo, Add(centre, -half));
            hi = fmaxf(hi, Add(centre, half));
        }
        box.min[i] = NextFloatDown(lo);
        box.max[i] = NextFloatUp(hi);
    }
    return box;
}

}  // namespace rtrt
