#pragma once
// The host-side scene a back end renders: BLASes shared between instances, instance records,
// materials, lights and camera; for an image of the scene as it is (renderer.h) also its own TLAS
// (a running scene's TLAS belongs to its FrameRenderer). The game extracts it from scene files or
// the ECS; render_rt knows nothing of either.
#include <memory>
#include <span>
#include <vector>

#include "engine/bvh/tlas/tlas.h"
#include "engine/render_rt/deformation.h"
#include "engine/render_rt/render_scene_view.h"

namespace rtrt {

// What changed in a RenderScene since a FrameRenderer last took it (frame_renderer.h).
struct SceneChanges {
    std::span<const uint32_t> instances;     // records rewritten or appended (indices)
    bool topologyChanged = false;            // instances were added or removed
    std::span<const uint32_t> deformations;  // deformation records whose pose changed (indices)
};

struct RenderScene {
    std::vector<std::shared_ptr<const Blas>> blases;
    std::vector<Instance> instances;
    std::vector<Material> materials;
    std::vector<PbrMaterial> pbrMaterials;
    std::vector<Light> lights;
    std::vector<Texture> textures;
    std::vector<uint32_t> texels;  // RGBA8 of every texture, one after another
    Camera camera;
    vec3 background{0.2f, 0.3f, 0.5f};
    uint32_t maxDepth = 4;
    // Deforming instances: each Deformation owns one BLAS slot of `blases` (which starts as its
    // mesh's rest tree); frame renderers deform and refit their own copy of it.
    std::vector<std::shared_ptr<const DeformableMesh>> deformableMeshes;
    std::vector<Deformation> deformations;

    uint32_t AddBlas(std::shared_ptr<const Blas> blas);
    uint32_t AddMaterial(const Material& material);
    // A glTF metallic-roughness material; approximation is what kernels without kFeaturePbr
    // (textures turned off) shade instead.
    uint32_t AddPbrMaterial(Material approximation, const PbrMaterial& pbr);
    // Appends width x height RGBA8 texels (row 0 the top), and its smaller mip levels after them
    // if texture.levels says so, as a texture; texelOffset is set here.
    uint32_t AddTexture(Texture texture, const uint32_t* rgba);
    // Appends texels for records to point at (AddTextureView); returns their offset.
    uint64_t AddTexels(const uint32_t* rgba, size_t count);
    // Another record over texels already added (the same image under another transform).
    uint32_t AddTextureView(const Texture& texture);
    uint32_t AddInstance(uint32_t blasId, uint32_t materialId, const glm::mat4& objectToWorld);
    uint32_t AddDeformableMesh(std::shared_ptr<const DeformableMesh> mesh);
    // A deformation of mesh `meshId` whose rest tree is BLAS `restBlasId` (built from the mesh,
    // same triangle order): appends a BLAS slot for it (the deformation's blasId, which its
    // instance uses) and the record, with the mesh's default morph weights. Returns its index.
    uint32_t AddDeformation(uint32_t meshId, uint32_t restBlasId);

    // Rebuilds the TLAS over the current instances; call after adding or moving instances.
    void BuildTlas();
    // Takes a TLAS built elsewhere over the current instances (tests, the accuracy study).
    void SetTlas(Tlas tlas);
    // The outline (blas_outline.h) of each BLAS from firstBlas on, for a TLAS over the instances:
    // a deformation's slot keeps no parts, as its frame renderer refits or rebuilds its tree.
    std::vector<BlasOutline> BlasOutlines(size_t firstBlas = 0) const;
    // The SceneFeature bits this scene's lights and the materials of its instances call for.
    uint32_t Features() const;
    uint64_t TriangleCount() const;  // over all instances

    const Tlas& GetTlas() const { return tlas_; }
    const std::vector<BlasView>& BlasViews() const { return blasViews_; }
    // View into host memory for the CPU back end.
    RenderSceneView HostView(uint32_t width, uint32_t height, uint32_t maxDepth) const;

  private:
    Tlas tlas_;
    std::vector<BlasView> blasViews_;
};

}  // namespace rtrt
