#pragma once
// The arrays of a RenderScene in device memory, for CUDA host code. DeviceScene holds what a
// running scene never changes (BLASes, materials, lights, textures); the TLAS and the instances
// belong to whoever keeps them up to date (the CUDA frame renderer), or, for an image of the scene
// as it is, to DeviceStaticScene.
#include <unordered_map>
#include <vector>

#include "engine/core/device_buffer.h"
#include "engine/render_rt/render_scene.h"
#include "engine/render_rt/render_settings.h"

namespace rtrt {

struct DeviceScene {
    std::vector<DeviceBuffer<BvhNode>> blasNodes;
    std::vector<DeviceBuffer<Triangle>> triangles;
    std::vector<DeviceBuffer<TriangleNormals>> normals;
    std::vector<DeviceBuffer<Sphere>> spheres;
    std::vector<DeviceBuffer<TriangleUvs>> uvs;
    std::vector<DeviceBuffer<TriangleTangents>> tangents;
    std::vector<DeviceBuffer<TriangleColors>> colors;
    DeviceBuffer<BlasView> blasViews;
    DeviceBuffer<Material> materials;
    DeviceBuffer<PbrMaterial> pbrMaterials;
    DeviceBuffer<Light> lights;
    DeviceBuffer<Texture> textures;
    DeviceBuffer<uint32_t> texels;

    explicit DeviceScene(const RenderScene& scene) {
        AddBlases(scene);
        materials.Upload(scene.materials);
        pbrMaterials.Upload(scene.pbrMaterials);
        lights.Upload(scene.lights);
        textures.Upload(scene.textures);
        texels.Upload(scene.texels);
    }

    // Uploads the BLASes the scene gained since (each distinct one once: slots that share a BLAS,
    // as deformations share their rest tree, share its copy). Returns whether any were added.
    bool AddBlases(const RenderScene& scene) {
        if (scene.blases.size() == views_.size()) return false;
        for (size_t id = views_.size(); id < scene.blases.size(); ++id) {
            const Blas* blas = scene.blases[id].get();
            auto known = uploaded_.find(blas);
            if (known != uploaded_.end()) {
                views_.push_back(known->second);
                continue;
            }
            blasNodes.emplace_back(std::span<const BvhNode>(blas->nodes));
            triangles.emplace_back(std::span<const Triangle>(blas->triangles));
            normals.emplace_back(std::span<const TriangleNormals>(blas->normals));
            spheres.emplace_back(std::span<const Sphere>(blas->spheres));
            uvs.emplace_back(std::span<const TriangleUvs>(blas->uvs));
            tangents.emplace_back(std::span<const TriangleTangents>(blas->tangents));
            colors.emplace_back(std::span<const TriangleColors>(blas->colors));
            BlasView v = blas->View();
            v.nodes = blasNodes.back().Data();
            v.nodes4 = nullptr;  // the GPU traverses the binary BVH
            v.triangles = triangles.back().Data();
            v.normals = blas->normals.empty() ? nullptr : normals.back().Data();
            v.spheres = spheres.back().Data();
            v.uvs = blas->uvs.empty() ? nullptr : uvs.back().Data();
            v.tangents = blas->tangents.empty() ? nullptr : tangents.back().Data();
            v.colors = blas->colors.empty() ? nullptr : colors.back().Data();
            uploaded_[blas] = v;
            views_.push_back(v);
        }
        blasViews.Upload(views_);
        return true;
    }

    // Points BLAS slot `id` at arrays someone else keeps (a deformed BLAS); CommitViews sends
    // the changed table.
    void SetView(uint32_t id, const BlasView& view) { views_[id] = view; }
    void CommitViews() { blasViews.Upload(views_); }

    // The view with no TLAS or instances yet (view.tlas.blases is set): the caller supplies them.
    RenderSceneView View(const RenderScene& scene, const RenderSettings& s) const {
        RenderSceneView view = scene.HostView(s.width, s.height, s.maxDepth);
        view.samplesPerPixel = s.samplesPerPixel;
        view.tlas = {nullptr, nullptr, blasViews.Data()};
        view.materials = materials.Data();
        view.pbrMaterials = pbrMaterials.Data();
        view.lights = lights.Data();
        view.textures = textures.Data();
        view.texels = texels.Data();
        return view;
    }

  private:
    std::vector<BlasView> views_;
    std::unordered_map<const Blas*, BlasView> uploaded_;  // each distinct BLAS's copy
};

// A scene with its own TLAS and instances on the device: one image of it as it is.
struct DeviceStaticScene {
    DeviceScene scene;
    DeviceBuffer<BvhNode> tlasNodes;
    DeviceBuffer<Instance> instances;

    explicit DeviceStaticScene(const RenderScene& s) : scene(s) {
        tlasNodes.Upload(s.GetTlas().nodes);
        instances.Upload(s.instances);
    }

    RenderSceneView View(const RenderScene& s, const RenderSettings& settings) const {
        RenderSceneView view = scene.View(s, settings);
        view.tlas = {tlasNodes.Data(), instances.Data(), scene.blasViews.Data()};
        return view;
    }
};

}  // namespace rtrt
