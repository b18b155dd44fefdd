#include "engine/bvh/tlas/instance.h"

#include <glm/gtc/matrix_inverse.hpp>

namespace rtrt {

void SetTransform(Instance& inst, const glm::mat4& objectToWorld) {
    // GLM is column-major: m[col][row].
    const glm::mat4 inverse = glm::affineInverse(objectToWorld);
    for (int r = 0; r < 3; ++r)
        inst.inverseAndPosition.row[r] =
            vec4(inverse[0][r], inverse[1][r], inverse[2][r], objectToWorld[3][r]);
}

Instance MakeInstance(uint32_t blasId, uint32_t materialId, const glm::mat4& objectToWorld) {
    Instance inst{};
    SetTransform(inst, objectToWorld);
    inst.blasId = blasId;
    inst.materialId = materialId;
    return inst;
}

glm::mat4 ObjectToWorldMatrix(const Instance& inst) { return Mat4FromAffine(inst.ObjectToWorld()); }

}  // namespace rtrt
