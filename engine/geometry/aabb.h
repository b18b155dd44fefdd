#pragma once
#include "engine/core/math.h"

namespace rtrt {

struct Aabb {
    vec3 min{kInfinity};
    vec3 max{-kInfinity};

    RT_HD void Grow(vec3 p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    RT_HD void Grow(const Aabb& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    RT_HD bool IsEmpty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    RT_HD vec3 Extent() const { return max - min; }
    RT_HD vec3 Centroid() const { return 0.5f * (min + max); }
    // Surface area; 0 for an empty box, so empty children cost nothing in the SAH.
    RT_HD float Area() const {
        if (IsEmpty()) return 0.0f;
        vec3 e = max - min;
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
    RT_HD bool Contains(const Aabb& b) const {
        return b.min.x >= min.x && b.min.y >= min.y && b.min.z >= min.z && b.max.x <= max.x &&
               b.max.y <= max.y && b.max.z <= max.z;
    }
};

}  // namespace rtrt
