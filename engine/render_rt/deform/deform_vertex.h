#pragma once
// One vertex of a deforming mesh in its deformed pose: morph targets, then the procedural
// deformation, then the skin (glTF's order: morphing happens in the mesh's rest space, skinning
// last). Normals follow each step by its inverse transpose, so they stay perpendicular to the
// deformed surface. Shared RT_HD code: the CPU and CUDA deformers run the same function.
#include "engine/core/affine.h"
#include "engine/render_rt/deformation.h"

namespace rtrt {

// Pointers to one deformable mesh's arrays, in host or device memory.
struct DeformMeshView {
    const vec3* positions;
    const vec3* normals;  // null: the mesh is flat shaded
    const glm::uvec3* indices;
    const vec2* uvs;         // null: untextured
    const vec3* colors;      // null: no vertex colours
    const uint32_t* joints;  // vertexCount x influences
    const float* weights;
    const vec3* positionDeltas;  // targetCount x vertexCount
    const vec3* normalDeltas;    // null or targetCount x vertexCount
    uint32_t vertexCount, triangleCount, influences, targetCount;
};

// The pose of one deformation this frame, as the deformer hands it to the device.
struct DeformPose {
    ProceduralDeform procedural;
    const Affine* joints;  // the deformation's joint matrices
    const float* morphWeights;
};

RT_HD inline vec3 AxisVector(uint32_t axis) {
    return vec3(axis == 0 ? 1.0f : 0.0f, axis == 1 ? 1.0f : 0.0f, axis == 2 ? 1.0f : 0.0f);
}

// Rodrigues' rotation of d about unit axis e by the angle whose cosine and sine are c and s.
RT_HD inline vec3 RotateAbout(vec3 d, vec3 e, float c, float s) {
    return d * c + glm::cross(e, d) * s + e * (glm::dot(e, d) * (1.0f - c));
}

RT_HD inline void ApplyProcedural(const ProceduralDeform& f, vec3& p, vec3& n) {
    constexpr float kTwoPi = 6.28318530717958647692f;
    if (f.kind == ProceduralDeformKind::kWave) {
        const float k = kTwoPi / f.wavelength;
        const float phase = k * ((p[f.along] - f.centre[f.along]) - f.speed * f.time);
        p[f.axis] += f.amplitude * sinf(phase);
        // The Jacobian is I + e_axis (A k cos(phase)) e_along^T; its inverse transpose moves
        // the normal's along-component by the slope times its axis-component.
        n[f.along] -= f.amplitude * k * cosf(phase) * n[f.axis];
    } else if (f.kind == ProceduralDeformKind::kTwist) {
        const vec3 e = AxisVector(f.axis);
        const float rate = f.amplitude * sinf(f.speed * f.time);  // radians per unit along e
        const vec3 d = p - f.centre;
        const float angle = rate * d[f.axis];
        const float c = cosf(angle), s = sinf(angle);
        // J = R + R (e x d) rate e^T, so J^-T n = R (n - e rate ((e x d) . n)).
        n = RotateAbout(n - e * (rate * glm::dot(glm::cross(e, d), n)), e, c, s);
        // Moved by the rotation's offset rather than rebuilt from the centre, which rounds at
        // the centre's magnitude: no twist is exactly no change, however far the centre.
        p += RotateAbout(d, e, c, s) - d;
    }
}

// The joint matrices of a vertex blended by its weights (linear blend skinning).
RT_HD inline Affine BlendJoints(const DeformMeshView& mesh, const DeformPose& pose, uint32_t v) {
    Affine m;
    m.row[0] = m.row[1] = m.row[2] = vec4(0.0f);
    for (uint32_t i = 0; i < mesh.influences; ++i) {
        const float w = mesh.weights[size_t(v) * mesh.influences + i];
        if (w == 0.0f) continue;
        const Affine& j = pose.joints[mesh.joints[size_t(v) * mesh.influences + i]];
        for (int r = 0; r < 3; ++r) m.row[r] += w * j.row[r];
    }
    return m;
}

// The normal through a linear map with rows r0, r1, r2: the cofactor matrix (the inverse
// transpose times the determinant), with the determinant's sign kept so mirrors do not flip it.
RT_HD inline vec3 NormalThrough(const Affine& m, vec3 n) {
    const vec3 r0(m.row[0]), r1(m.row[1]), r2(m.row[2]);
    const vec3 c0 = glm::cross(r1, r2), c1 = glm::cross(r2, r0), c2 = glm::cross(r0, r1);
    const float det = glm::dot(r0, c0);
    const vec3 out(glm::dot(c0, n), glm::dot(c1, n), glm::dot(c2, n));
    return det < 0.0f ? -out : out;
}

RT_HD inline vec3 SafeNormalize(vec3 n) {
    const float len2 = glm::dot(n, n);
    return len2 > 0.0f ? n * (1.0f / sqrtf(len2)) : n;
}

// Vertex v of the mesh in the pose; *normal gets its unit normal when the mesh has normals.
RT_HD inline vec3 DeformVertex(const DeformMeshView& mesh, const DeformPose& pose, uint32_t v,
                               vec3* normal) {
    vec3 p = mesh.positions[v];
    vec3 n = mesh.normals ? mesh.normals[v] : vec3(0.0f);
    for (uint32_t t = 0; t < mesh.targetCount; ++t) {
        const float w = pose.morphWeights[t];
        if (w == 0.0f) continue;
        const size_t at = size_t(t) * mesh.vertexCount + v;
        p += w * mesh.positionDeltas[at];
        if (mesh.normalDeltas) n += w * mesh.normalDeltas[at];
    }
    ApplyProcedural(pose.procedural, p, n);
    if (mesh.influences > 0) {
        const Affine m = BlendJoints(mesh, pose, v);
        p = m.Point(p);
        n = NormalThrough(m, n);
    }
    *normal = SafeNormalize(n);
    return p;
}

}  // namespace rtrt
