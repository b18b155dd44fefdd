#pragma once
#include "engine/core/math.h"

namespace rtrt {

// A ray o + t d for t in [0, tMax]. d need not be unit length: instance transforms keep t
// comparable between world and object space by not renormalising.
struct Ray {
    vec3 origin;
    float tMax;
    vec3 dir;
    float pad;
};
static_assert(sizeof(Ray) == 32);

}  // namespace rtrt
