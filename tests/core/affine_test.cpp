// The 3x4 instance transform: exact on representable values, and its inverse maps normals.
#include "engine/core/affine.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace rtrt {
namespace {

TEST(Affine, PointsAndVectorsOfAScaleAndTranslation) {
    const glm::mat4 m = glm::scale(glm::translate(glm::mat4(1.0f), vec3(1, 2, 3)), vec3(2, 4, 8));
    const Affine a = AffineFromMat4(m);
    EXPECT_EQ(a.Point(vec3(1, 1, 1)), vec3(3, 6, 11));
    EXPECT_EQ(a.Vector(vec3(1, 1, 1)), vec3(2, 4, 8));
    EXPECT_EQ(Mat4FromAffine(a), m);
    EXPECT_EQ(Affine::Identity().Point(vec3(5, -6, 7)), vec3(5, -6, 7));
}

// A normal transforms by the inverse transpose: on the scale (2, 4, 8) the normal (1, 1, 1)
// becomes (1/2, 1/4, 1/8), all exact in binary.
TEST(Affine, NormalsTransformByTheInverseTranspose) {
    const glm::mat4 inverse = glm::scale(glm::mat4(1.0f), vec3(0.5f, 0.25f, 0.125f));
    EXPECT_EQ(AffineFromMat4(inverse).NormalFromInverse(vec3(1, 1, 1)), vec3(0.5f, 0.25f, 0.125f));
}

// Each row's error bound is gamma(3) of its terms' magnitudes (pbrt-v4's Point3fi transform).
TEST(Affine, PointErrorOfAnExactPoint) {
    const Affine a = AffineFromMat4(glm::translate(glm::mat4(1.0f), vec3(4, 0, 0)));
    const vec3 err = a.PointError(vec3(1, 2, 3), vec3(0));
    EXPECT_FLOAT_EQ(err.x, Gamma(3) * 5.0f);
    EXPECT_FLOAT_EQ(err.y, Gamma(3) * 2.0f);
    EXPECT_FLOAT_EQ(err.z, Gamma(3) * 3.0f);
}

}  // namespace
}  // namespace rtrt
