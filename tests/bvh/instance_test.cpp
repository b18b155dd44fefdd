// The instance record keeps L^-1 and the position; the way back to world space inverts L^-1.
#include "engine/bvh/tlas/instance.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace rtrt {
namespace {

glm::mat4 Placement() {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), vec3(1e4f, -3.25f, 0.5f));
    m = glm::rotate(m, 0.7f, glm::normalize(vec3(1.0f, 2.0f, -0.5f)));
    return glm::scale(m, vec3(2.0f, 0.25f, 3.0f));
}

TEST(Instance, KeepsTheInverseAndThePositionExactly) {
    const glm::mat4 m = Placement();
    const Instance inst = MakeInstance(7, 3, m);
    EXPECT_EQ(inst.blasId, 7u);
    EXPECT_EQ(inst.materialId, 3u);
    EXPECT_EQ(inst.Position(), vec3(m[3]));
    const glm::mat4 inverse = glm::affineInverse(m);
    for (int r = 0; r < 3; ++r)
        EXPECT_EQ(inst.InverseRow(r), vec3(inverse[0][r], inverse[1][r], inverse[2][r])) << r;
}

TEST(Instance, ObjectToWorldInvertsTheInverse) {
    const glm::mat4 m = Placement();
    const Instance inst = MakeInstance(0, 0, m);
    const Affine toWorld = inst.ObjectToWorld();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(toWorld.row[r][c], m[c][r], 1e-6f * 3.0f) << r << c;
        EXPECT_EQ(toWorld.row[r].w, m[3][r]) << r;  // the position is not computed
    }
    // There and back: an object-space offset to world space and back again.
    const vec3 v(0.3f, -1.7f, 2.2f);
    const vec3 back = inst.VectorToObject(toWorld.Vector(v));
    EXPECT_NEAR(glm::length(back - v), 0.0f, 1e-5f);
    // Normals go by the inverse's transpose: perpendicular to world tangents.
    const vec3 n = inst.NormalToWorld(vec3(0.0f, 0.0f, 1.0f));
    EXPECT_NEAR(glm::dot(n, toWorld.Vector(vec3(1.0f, 0.0f, 0.0f))), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(n, toWorld.Vector(vec3(0.0f, 1.0f, 0.0f))), 0.0f, 1e-6f);
}

TEST(Instance, IdentityAndTranslationsComeBackExactly) {
    const glm::mat4 m = glm::translate(glm::mat4(1.0f), vec3(-2.0f, 5.0f, 1e6f));
    const Affine toWorld = MakeInstance(0, 0, m).ObjectToWorld();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) EXPECT_EQ(toWorld.row[r][c], m[c][r]) << r << c;
    EXPECT_EQ(ObjectToWorldMatrix(MakeInstance(0, 0, glm::mat4(1.0f))), glm::mat4(1.0f));
}

}  // namespace
}  // namespace rtrt
