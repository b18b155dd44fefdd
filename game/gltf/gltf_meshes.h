#pragma once
// glTF meshes: each triangle primitive becomes a BLAS with its material, and a skinned or morphed
// one also a DeformableMesh (its rest pose, the triangles of that BLAS in the same order); other
// primitive modes and compressed primitives are skipped with a warning.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/geometry/triangle_mesh.h"
#include "game/gltf/gltf_asset.h"
#include "game/gltf/gltf_document.h"
#include "game/gltf/gltf_materials.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

// The triangles of a TRIANGLE_STRIP (fan = false) or TRIANGLE_FAN index list, in the
// specification's order, degenerate ones left out.
std::vector<glm::uvec3> StripOrFanTriangles(const std::vector<uint32_t>& indices, bool fan);

class GltfMeshes {
  public:
    // Adds BLASes and materials to OUT and counts what it reads in SUMMARY.
    GltfMeshes(GltfDocument& doc, LoadedScene& out, GltfMaterials& materials, GltfSummary& summary)
        : doc_(doc), model_(doc.Model()), out_(out), materials_(materials), summary_(summary) {}

    // The triangle primitives of MESH as a node with skin SKIN (-1: none) shows them, built on
    // first use: a mesh skinned by two skins is read twice, since its joint indices refer to
    // each skin's joints.
    std::vector<GltfPrimitive> Primitives(size_t mesh, int skin);

  private:
    TriangleMesh ReadPrimitive(const tinygltf::Primitive& prim, const std::string& at);
    // COLOR_0 (accessor ACCESSOR, named FIELD) as linear RGB per vertex, for a primitive of
    // VERTICES vertices; empty, with a warning, where rtrt cannot read it (a sparse accessor).
    std::vector<vec3> ReadVertexColors(int accessor, const std::string& field, size_t vertices);
    // Whether the primitive's material samples any texture.
    bool Textured(const tinygltf::Primitive& prim) const;
    // Whether the primitive's material has a normal map (its triangles then carry tangents).
    bool NormalMapped(const tinygltf::Primitive& prim) const;
    // Vertex tangents for a normal-mapped primitive that does not deform: the file's TANGENT,
    // else generated (GenerateTangents). Deforming ones keep per-face tangents, taken from their
    // deformed triangles at each hit, where stored ones would go stale.
    void AddTangents(const tinygltf::Primitive& prim, const std::string& at, int skin,
                     TriangleMesh& mesh);
    // Registers the primitive as a deformable mesh when it is skinned (SKIN >= 0 and it has
    // joints) or has morph targets.
    void ReadDeformation(const tinygltf::Primitive& prim, const std::string& at, size_t mesh,
                         int skin, const TriangleMesh& triangles, GltfPrimitive& out);

    GltfDocument& doc_;
    const tinygltf::Model& model_;
    LoadedScene& out_;
    GltfMaterials& materials_;
    GltfSummary& summary_;
    std::map<std::pair<size_t, int>, std::vector<GltfPrimitive>> meshPrimitives_;
    // A BLAS and its counts, by the accessors of a primitive without morph targets or a skin:
    // primitives that name the same accessors share it, as 600 primitives of one 100,000-triangle
    // accessor otherwise built 600 trees (out of memory from a 20 KB file).
    struct StaticGeometry {
        uint32_t blas = 0, vertices = 0, triangles = 0;
    };
    std::map<std::string, StaticGeometry> staticGeometry_;
    uint64_t morphDeltas_ = 0;  // read by all primitives so far (ReadGltfMorphTargets)
};

}  // namespace rtrt
