#pragma once
#include "engine/core/affine.h"

namespace rtrt {

// One placed copy of a BLAS, 112 bytes: both transforms so that neither side inverts per ray.
struct Instance {
    Affine objectToWorld;
    Affine worldToObject;
    uint32_t blasId;
    uint32_t materialId;
    uint32_t pad[2];
};
static_assert(sizeof(Instance) == 112);

}  // namespace rtrt
