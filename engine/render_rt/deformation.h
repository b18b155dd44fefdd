#pragma once
// The pose of one deforming instance: which deformable mesh it shows, the BLAS slot it owns (its
// own vertices and tree, which the frame renderer skins or morphs and refits), and what deforms
// it this frame. The runtime writes these records; the frame renderer turns them into triangles.
#include <cstdint>
#include <vector>

#include "engine/core/affine.h"
#include "engine/geometry/deformable_mesh.h"

namespace rtrt {

enum class ProceduralDeformKind : uint32_t { kNone = 0, kWave = 1, kTwist = 2 };

// A deformation computed from a formula, in the mesh's own space, after morphing and before
// skinning.
//   wave:  p[axis] += amplitude * sin(2 pi ((p[along] - centre[along]) - speed * time) /
//   wavelength) twist: p turns about the line through centre along `axis` by
//          amplitude * sin(speed * time) * (p[axis] - centre[axis]) radians
// Normals follow by the deformation's Jacobian (the exact derivative of the formula).
struct ProceduralDeform {
    ProceduralDeformKind kind = ProceduralDeformKind::kNone;
    uint32_t axis = 1;   // 0, 1, 2: x, y, z
    uint32_t along = 0;  // wave only
    float amplitude = 0.0f;
    float wavelength = 1.0f;  // wave only, > 0
    float speed = 1.0f;
    float time = 0.0f;  // seconds
    vec3 centre{0.0f};
};

struct Deformation {
    uint32_t mesh = 0;    // index in RenderScene::deformableMeshes
    uint32_t blasId = 0;  // the instance's own BLAS slot (the mesh's rest tree until deformed)
    ProceduralDeform procedural;
    // Skin: one matrix per joint of the mesh, from the rest mesh's space to the deformed mesh's
    // space, the instance's frame (glTF: inverse(the mesh node's frame) * world of the joint *
    // inverse bind matrix; physics_anim/skinning.h's SkinnedMeshFrame).
    std::vector<Affine> jointMatrices;
    std::vector<float> morphWeights;  // one per morph target of the mesh
};

// When a deforming BLAS is rebuilt rather than refit: its tree's SAH cost is watched after every
// refit, and once it exceeds (1 + maxSahGrowth) x the cost right after the tree's last build, the
// tree is rebuilt (an LBVH over the deformed triangles, on the device that deforms them).
struct BlasRebuildPolicy {
    enum class Mode : uint8_t { kAdaptive, kAlwaysRefit, kAlwaysRebuild };
    Mode mode = Mode::kAdaptive;
    float maxSahGrowth = 0.2f;
};

}  // namespace rtrt
