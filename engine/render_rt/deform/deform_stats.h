#pragma once
// What bringing the deforming BLASes up to date cost in one frame.
#include <cstdint>

namespace rtrt {

struct DeformStats {
    double deformMs = 0.0;   // skinning, morphing, procedural deformation, leaf-ordered triangles
    double blasMs = 0.0;     // refits, rebuilds and their SAH costs
    uint32_t deformed = 0;   // deformations updated
    uint32_t rebuilt = 0;    // of them rebuilt rather than refit
    uint64_t triangles = 0;  // triangles of the updated deformations
};

}  // namespace rtrt
