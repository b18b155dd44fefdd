#pragma once
#include "engine/core/float_bounds.h"
#include "engine/core/math.h"

namespace rtrt {

// A 3x4 affine transform stored as three rows (linear part | translation), 48 bytes, the layout
// instance records keep on the GPU.
struct Affine {
    vec4 row[3];

    RT_HD static Affine Identity() {
        return {{vec4(1, 0, 0, 0), vec4(0, 1, 0, 0), vec4(0, 0, 1, 0)}};
    }
    RT_HD vec3 Point(vec3 p) const {
        return vec3(Dot3(row[0], p) + row[0].w, Dot3(row[1], p) + row[1].w,
                    Dot3(row[2], p) + row[2].w);
    }
    RT_HD vec3 Vector(vec3 v) const {
        return vec3(Dot3(row[0], v), Dot3(row[1], v), Dot3(row[2], v));
    }
    // Multiplies a normal by the transpose of this (inverse) transform.
    RT_HD vec3 NormalFromInverse(vec3 n) const {
        return vec3(row[0].x * n.x + row[1].x * n.y + row[2].x * n.z,
                    row[0].y * n.x + row[1].y * n.y + row[2].y * n.z,
                    row[0].z * n.x + row[1].z * n.y + row[2].z * n.z);
    }
    // Transforms point p carrying absolute error pError; returns the bound on the result's error
    // (pbrt-v4, "Transform::operator()(Point3fi)": gamma(3) per row plus the propagated error).
    RT_HD vec3 PointError(vec3 p, vec3 pError) const {
        vec3 err;
        for (int i = 0; i < 3; ++i) {
            const vec4& r = row[i];
            float roundOff = fabsf(r.x * p.x) + fabsf(r.y * p.y) + fabsf(r.z * p.z) + fabsf(r.w);
            float carried = fabsf(r.x) * pError.x + fabsf(r.y) * pError.y + fabsf(r.z) * pError.z;
            err[i] = Gamma(3) * roundOff + (Gamma(3) + 1.0f) * carried;
        }
        return err;
    }

  private:
    RT_HD static float Dot3(const vec4& r, vec3 v) { return r.x * v.x + r.y * v.y + r.z * v.z; }
};
static_assert(sizeof(Affine) == 48);

// Host-side helpers for building transforms from GLM matrices.
Affine AffineFromMat4(const glm::mat4& m);
glm::mat4 Mat4FromAffine(const Affine& a);

}  // namespace rtrt
