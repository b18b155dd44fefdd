#pragma once
#include "engine/core/affine.h"

namespace rtrt {

// One placed copy of a BLAS, 64 bytes. Its transform objectToWorld (p -> L p + c) is kept as the
// traversal uses it: the inverse L^-1 of the linear part and the world position c, so that
// entering an instance loads 48 bytes and inverts nothing. The way back to world space (hit
// points, tangents, world boxes) inverts L^-1 again, once per hit or per box. Both transforms
// took 112 bytes; the traversal never read the forward one.
struct alignas(16) Instance {
    // xyz of row i: row i of L^-1; w: coordinate i of c. Not an affine map itself: only its
    // linear part is applied (Vector, NormalFromInverse), to offsets from c.
    Affine inverseAndPosition;
    uint32_t blasId;
    uint32_t materialId;
    // Not the instance's: two words of the GPU TLAS's own (gpu_tlas.h), which has one pair of
    // nodes per instance and keeps each pair's parent link here rather than in an array of its
    // own. Writers of a placement leave them alone (SetPlacement); no traversal reads them.
    uint32_t tlasWords[2];

    RT_HD vec3 Position() const {
        const vec4* r = inverseAndPosition.row;
        return vec3(r[0].w, r[1].w, r[2].w);
    }
    // Row i of L^-1.
    RT_HD vec3 InverseRow(int i) const { return vec3(inverseAndPosition.row[i]); }
    // L^-1 v: a world direction (or an offset from the position) in object space.
    RT_HD vec3 VectorToObject(vec3 v) const { return inverseAndPosition.Vector(v); }
    // L^-T n: an object-space normal in world space (unnormalised).
    RT_HD vec3 NormalToWorld(vec3 n) const { return inverseAndPosition.NormalFromInverse(n); }
    // objectToWorld, its linear part the inverse of L^-1 (cofactors over the determinant).
    RT_HD Affine ObjectToWorld() const {
        const vec3 a = InverseRow(0), b = InverseRow(1), d = InverseRow(2);
        // The columns of (L^-1)^-1 are the rows' pairwise cross products over the determinant.
        const vec3 c0 = glm::cross(b, d), c1 = glm::cross(d, a), c2 = glm::cross(a, b);
        const float inv = 1.0f / glm::dot(a, c0);
        const vec3 p = Position();
        Affine m;
        m.row[0] = vec4(c0.x * inv, c1.x * inv, c2.x * inv, p.x);
        m.row[1] = vec4(c0.y * inv, c1.y * inv, c2.y * inv, p.y);
        m.row[2] = vec4(c0.z * inv, c1.z * inv, c2.z * inv, p.z);
        return m;
    }
};
static_assert(sizeof(Instance) == 64);

// An instance of blasId with materialId placed by objectToWorld (an invertible affine matrix):
// L^-1 as glm::affineInverse computes it, c as given.
Instance MakeInstance(uint32_t blasId, uint32_t materialId, const glm::mat4& objectToWorld);
// Copies src's placement and ids into dst, leaving dst's TLAS words as they are.
RT_HD inline void SetPlacement(Instance& dst, const Instance& src) {
    dst.inverseAndPosition = src.inverseAndPosition;
    dst.blasId = src.blasId;
    dst.materialId = src.materialId;
}
// Places inst by objectToWorld, keeping its ids.
void SetTransform(Instance& inst, const glm::mat4& objectToWorld);
// inst's objectToWorld as a matrix (Instance::ObjectToWorld).
glm::mat4 ObjectToWorldMatrix(const Instance& inst);

}  // namespace rtrt
