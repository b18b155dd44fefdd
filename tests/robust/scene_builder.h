#pragma once
// Small RenderScenes for the cases: BLASes from meshes or spheres, instances from matrices.
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <span>

#include "engine/render_rt/render_scene.h"

namespace rtrt::robust {

inline uint32_t AddMeshBlas(RenderScene& scene, const TriangleMesh& mesh) {
    return scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(mesh)));
}

inline uint32_t AddSphereBlas(RenderScene& scene, std::span<const Sphere> spheres) {
    return scene.AddBlas(std::make_shared<const Blas>(BuildSphereBlas(spheres)));
}

// Translation t, then rotation by `radians` about `axis` (applied to the object first).
inline glm::mat4 Placement(vec3 t, float radians = 0.0f, vec3 axis = vec3(0, 1, 0)) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), t);
    if (radians != 0.0f) m = glm::rotate(m, radians, glm::normalize(axis));
    return m;
}

inline vec3 TransformPoint(const glm::mat4& m, vec3 p) { return vec3(m * glm::vec4(p, 1.0f)); }

// A unit vector perpendicular to the unit vector n.
inline vec3 Perpendicular(vec3 n) {
    return glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0)));
}

}  // namespace rtrt::robust
