#pragma once
// glTF meshes: each triangle primitive becomes a BLAS with its material; other primitive modes,
// morph targets and compressed primitives are skipped with a warning.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/geometry/triangle_mesh.h"
#include "game/gltf/gltf_document.h"
#include "game/gltf/gltf_materials.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

class GltfMeshes {
  public:
    // Adds BLASes and materials to OUT and counts what it reads in SUMMARY.
    GltfMeshes(GltfDocument& doc, LoadedScene& out, GltfMaterials& materials, GltfSummary& summary)
        : doc_(doc), model_(doc.Model()), out_(out), materials_(materials), summary_(summary) {}

    // The BLAS and material of each triangle primitive of MESH, built on first use.
    std::vector<std::pair<uint32_t, uint32_t>> Primitives(size_t mesh);

  private:
    TriangleMesh ReadPrimitive(const tinygltf::Primitive& prim, const std::string& at);

    GltfDocument& doc_;
    const tinygltf::Model& model_;
    LoadedScene& out_;
    GltfMaterials& materials_;
    GltfSummary& summary_;
    std::map<size_t, std::vector<std::pair<uint32_t, uint32_t>>> meshPrimitives_;
};

}  // namespace rtrt
