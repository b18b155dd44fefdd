#include "engine/core/affine.h"

namespace rtrt {

Affine AffineFromMat4(const glm::mat4& m) {
    // GLM is column-major: m[col][row].
    Affine a;
    for (int r = 0; r < 3; ++r) a.row[r] = vec4(m[0][r], m[1][r], m[2][r], m[3][r]);
    return a;
}

glm::mat4 Mat4FromAffine(const Affine& a) {
    glm::mat4 m(1.0f);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = a.row[r][c];
    return m;
}

}  // namespace rtrt
