#pragma once
// A mesh that deforms: its rest pose (the indexed mesh its BLAS was built from, in the same
// triangle order) and what moves it — a skin (linear blend skinning over joints) and morph
// targets (position and normal deltas). Shared by every instance of the mesh; each instance's
// pose (joint matrices, morph weights, a procedural deformation) is a Deformation record
// (engine/render_rt/deformation.h).
#include <cstdint>
#include <vector>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

// The most joints one vertex follows: glTF's JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1 sets.
inline constexpr uint32_t kMaxInfluences = 8;

struct DeformableMesh {
    TriangleMesh rest;

    // Skin: `influences` (0, 4 or 8) joint indices and weights per vertex, vertex-major
    // (vertex v's are [v * influences, (v + 1) * influences)); the weights of a vertex sum to 1
    // and unused slots have weight 0. Joint indices are below jointCount.
    uint32_t influences = 0;
    uint32_t jointCount = 0;
    std::vector<uint32_t> joints;
    std::vector<float> weights;

    // Morph targets: targetCount blocks of one delta per vertex (target t's are
    // [t * vertexCount, (t + 1) * vertexCount)); normalDeltas is empty when no target moves
    // normals. defaultWeights holds targetCount weights (glTF's mesh.weights, else zeros).
    uint32_t targetCount = 0;
    std::vector<vec3> positionDeltas;
    std::vector<vec3> normalDeltas;
    std::vector<float> defaultWeights;

    uint32_t VertexCount() const { return uint32_t(rest.positions.size()); }
    bool Skinned() const { return influences > 0; }
};

}  // namespace rtrt
