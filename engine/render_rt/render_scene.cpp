#include "engine/render_rt/render_scene.h"

#include <algorithm>

#include "engine/render_rt/shading/pbr_brdf.h"

namespace rtrt {

uint32_t RenderScene::AddBlas(std::shared_ptr<const Blas> blas) {
    blases.push_back(std::move(blas));
    return uint32_t(blases.size() - 1);
}

uint32_t RenderScene::AddMaterial(const Material& material) {
    materials.push_back(material);
    return uint32_t(materials.size() - 1);
}

uint32_t RenderScene::AddPbrMaterial(Material approximation, const PbrMaterial& pbr) {
    pbrMaterials.push_back(pbr);
    approximation.pbrMaterial = uint32_t(pbrMaterials.size() - 1);
    return AddMaterial(approximation);
}

uint32_t RenderScene::AddTextureView(const Texture& texture) {
    textures.push_back(texture);
    return uint32_t(textures.size() - 1);
}

uint64_t RenderScene::AddTexels(const uint32_t* rgba, size_t count) {
    const uint64_t offset = texels.size();
    texels.insert(texels.end(), rgba, rgba + count);
    return offset;
}

uint32_t RenderScene::AddTexture(Texture texture, const uint32_t* rgba) {
    texture.texelOffset =
        AddTexels(rgba, TexelCount(texture.width, texture.height, texture.levels));
    textures.push_back(texture);
    return uint32_t(textures.size() - 1);
}

uint32_t RenderScene::AddInstance(uint32_t blasId, uint32_t materialId,
                                  const glm::mat4& objectToWorld) {
    instances.push_back(MakeInstance(blasId, materialId, objectToWorld));
    return uint32_t(instances.size() - 1);
}

uint32_t RenderScene::AddDeformableMesh(std::shared_ptr<const DeformableMesh> mesh) {
    deformableMeshes.push_back(std::move(mesh));
    return uint32_t(deformableMeshes.size() - 1);
}

uint32_t RenderScene::AddDeformation(uint32_t meshId, uint32_t restBlasId) {
    Deformation d;
    d.mesh = meshId;
    d.blasId = AddBlas(blases[restBlasId]);
    const DeformableMesh& mesh = *deformableMeshes[meshId];
    d.morphWeights = mesh.defaultWeights;
    d.jointMatrices.assign(mesh.jointCount, Affine::Identity());
    deformations.push_back(std::move(d));
    return uint32_t(deformations.size() - 1);
}

void RenderScene::BuildTlas() {
    std::vector<Aabb> blasBounds;
    blasViews_.clear();
    for (const auto& blas : blases) {
        blasBounds.push_back(blas->bounds);
        blasViews_.push_back(blas->View());
    }
    tlas_ = rtrt::BuildTlas(instances, blasBounds, TlasBuilder::kSah, BlasOutlines());
}

std::vector<BlasOutline> RenderScene::BlasOutlines(size_t firstBlas) const {
    std::vector<bool> deforms(blases.size(), false);
    for (const Deformation& d : deformations)
        if (d.blasId < deforms.size()) deforms[d.blasId] = true;
    std::vector<BlasOutline> outlines;
    for (size_t id = firstBlas; id < blases.size(); ++id)
        outlines.push_back(OutlineOfBlas(*blases[id], deforms[id]));
    return outlines;
}

void RenderScene::SetTlas(Tlas tlas) {
    blasViews_.clear();
    for (const auto& blas : blases) blasViews_.push_back(blas->View());
    tlas_ = std::move(tlas);
}

namespace {

// The features one material calls for. A metallic-roughness texture can lower roughness and
// metalness anywhere below their factors.
uint32_t MaterialFeatures(const Material& m, const std::vector<PbrMaterial>& pbrMaterials) {
    uint32_t features = 0;
    if (m.reflectivity > 0.0f) features |= kFeatureReflection;
    if (m.transmissivity > 0.0f) features |= kFeatureRefraction | kFeatureReflection;
    if (m.baseColorTexture != kNoTexture) features |= kFeatureTextures;
    if (m.pbrMaterial == kNoPbrMaterial) return features;
    const PbrMaterial& p = pbrMaterials[m.pbrMaterial];
    const bool textured = p.metallicRoughnessTexture != kNoTexture;
    features |= kFeaturePbr | kFeatureTextures;  // IsKernelFeatureSet
    if (textured || MirrorShare(p.roughness) > 0.0f) features |= kFeatureReflection;
    if (p.transmission > 0.0f && (textured || p.metallic < 1.0f))
        features |= kFeatureRefraction | kFeatureReflection;
    return features;
}

// Up to this many instances, only the materials they use count (a window's spawn palette holds
// materials nothing may use yet); beyond it, every material, without a pass over the instances.
constexpr size_t kMaterialUseScanLimit = 65536;

}  // namespace

uint32_t RenderScene::Features() const {
    uint32_t features = lights.empty() ? 0u : kFeatureShadows;
    features |= InstanceCountFeatures(instances.size());
    // Vertex colours are applied where textures are (MaterialAt, PbrInputsAt).
    auto colored = [](const std::shared_ptr<const Blas>& b) { return !b->colors.empty(); };
    if (instances.size() > kMaterialUseScanLimit) {
        for (const Material& m : materials) features |= MaterialFeatures(m, pbrMaterials);
        if (std::any_of(blases.begin(), blases.end(), colored)) features |= kFeatureTextures;
        return features;
    }
    std::vector<bool> used(materials.size(), false);
    for (const Instance& inst : instances) {
        if (inst.materialId < used.size() && !used[inst.materialId]) {
            used[inst.materialId] = true;
            features |= MaterialFeatures(materials[inst.materialId], pbrMaterials);
        }
        if (inst.blasId < blases.size() && colored(blases[inst.blasId]))
            features |= kFeatureTextures;
    }
    return features;
}

uint64_t RenderScene::TriangleCount() const {
    uint64_t count = 0;
    for (const Instance& inst : instances) {
        const Blas& blas = *blases[inst.blasId];
        if (blas.kind == GeometryKind::kTriangles) count += blas.PrimCount();
    }
    return count;
}

RenderSceneView RenderScene::HostView(uint32_t width, uint32_t height, uint32_t depth) const {
    RenderSceneView view;
    view.tlas = {tlas_.nodes.data(), instances.data(), blasViews_.data()};
    view.materials = materials.data();
    view.pbrMaterials = pbrMaterials.data();
    view.lights = lights.data();
    view.textures = textures.data();
    view.texels = texels.data();
    view.lightCount = uint32_t(lights.size());
    view.maxDepth = std::clamp(depth, 1u, kMaxRayDepth);
    view.camera = MakeCameraFrame(camera, width, height);
    view.background = background;
    view.width = width;
    view.height = height;
    view.samplesPerPixel = 1;
    return view;
}

}  // namespace rtrt
