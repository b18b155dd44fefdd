#pragma once
#include <vector>

#include "engine/core/math.h"

namespace rtrt {

// A linear RGB float image, rows top to bottom.
struct Image {
    uint32_t width = 0, height = 0;
    std::vector<vec3> pixels;

    Image() = default;
    Image(uint32_t w, uint32_t h) : width(w), height(h), pixels(size_t(w) * h, vec3(0.0f)) {}
    vec3& At(uint32_t x, uint32_t y) { return pixels[size_t(y) * width + x]; }
    const vec3& At(uint32_t x, uint32_t y) const { return pixels[size_t(y) * width + x]; }
};

}  // namespace rtrt
