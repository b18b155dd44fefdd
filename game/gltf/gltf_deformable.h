#pragma once
// What makes a glTF primitive deform: its skin influences (JOINTS_n / WEIGHTS_n) and its morph
// targets (POSITION and NORMAL deltas), read into a DeformableMesh.
#include <cstdint>
#include <string>

#include "engine/geometry/deformable_mesh.h"
#include "game/gltf/gltf_document.h"

namespace rtrt {

// Reads JOINTS_0/WEIGHTS_0 and, where present, JOINTS_1/WEIGHTS_1 of PRIM (at field AT) for a
// skin of jointCount joints into out.influences/joints/weights/jointCount; out.rest must hold
// the primitive's vertices. Each vertex's weights are normalised to sum 1. A vertex whose weights
// are all zero follows the mesh's own node, unskinned: it gets weight 1 on an extra joint, index
// jointCount, whose matrix is the identity (the skin's joints then number jointCount + 1, and
// the function returns true in nodeJoint). False, with a warning, when the primitive has no
// JOINTS_0 (it is drawn unskinned) or uses what rtrt skips (sparse accessors). Throws
// InputError for malformed influences (wrong component types, counts, joints out of range,
// negative or non-finite weights).
bool ReadGltfSkinInfluences(GltfDocument& doc, const tinygltf::Primitive& prim,
                            const std::string& at, uint32_t jointCount, DeformableMesh& out,
                            bool& nodeJoint);

// Reads PRIM's morph targets into out.targetCount/positionDeltas/normalDeltas/defaultWeights
// (the mesh's `weights`, else zeros; MESH_AT names the mesh); out.rest must hold the
// primitive's vertices and normals (normal deltas are dropped for a mesh without normals).
// False when the primitive has none, or uses what rtrt skips (with a warning); throws
// InputError for malformed targets.
// fileDeltas: the deltas the file's primitives have read so far; the file may hold 2^26 in all.
bool ReadGltfMorphTargets(GltfDocument& doc, const tinygltf::Primitive& prim, const std::string& at,
                          const tinygltf::Mesh& mesh, const std::string& meshAt,
                          DeformableMesh& out, uint64_t& fileDeltas);

}  // namespace rtrt
