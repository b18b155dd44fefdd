#pragma once
// The arrays of a RenderScene in device memory (BLASes, TLAS, instances, materials, lights,
// textures), for
// CUDA host code. The BLASes go up once; a frame loop replaces only what changed.
#include <vector>

#include "engine/core/device_buffer.h"
#include "engine/render_rt/renderer.h"

namespace rtrt {

struct DeviceScene {
    std::vector<DeviceBuffer<BvhNode>> blasNodes;
    std::vector<DeviceBuffer<Triangle>> triangles;
    std::vector<DeviceBuffer<TriangleNormals>> normals;
    std::vector<DeviceBuffer<Sphere>> spheres;
    std::vector<DeviceBuffer<TriangleUvs>> uvs;
    DeviceBuffer<BlasView> blasViews;
    DeviceBuffer<BvhNode> tlasNodes;
    DeviceBuffer<uint32_t> instanceOrder;
    DeviceBuffer<Instance> instances;
    DeviceBuffer<Material> materials;
    DeviceBuffer<Light> lights;
    DeviceBuffer<Texture> textures;
    DeviceBuffer<uint32_t> texels;

    explicit DeviceScene(const RenderScene& scene) {
        std::vector<BlasView> views;
        for (const auto& blas : scene.blases) {
            blasNodes.emplace_back(std::span<const BvhNode>(blas->nodes));
            triangles.emplace_back(std::span<const Triangle>(blas->triangles));
            normals.emplace_back(std::span<const TriangleNormals>(blas->normals));
            spheres.emplace_back(std::span<const Sphere>(blas->spheres));
            uvs.emplace_back(std::span<const TriangleUvs>(blas->uvs));
            BlasView v = blas->View();
            v.nodes = blasNodes.back().Data();
            v.nodes4 = nullptr;  // the GPU traverses the binary BVH
            v.triangles = triangles.back().Data();
            v.normals = blas->normals.empty() ? nullptr : normals.back().Data();
            v.spheres = spheres.back().Data();
            v.uvs = blas->uvs.empty() ? nullptr : uvs.back().Data();
            views.push_back(v);
        }
        blasViews.Upload(views);
        tlasNodes.Upload(scene.GetTlas().nodes);
        instanceOrder.Upload(scene.GetTlas().instanceOrder);
        instances.Upload(scene.instances);
        materials.Upload(scene.materials);
        lights.Upload(scene.lights);
        textures.Upload(scene.textures);
        texels.Upload(scene.texels);
    }

    RenderSceneView View(const RenderScene& scene, const RenderSettings& s) const {
        RenderSceneView view = scene.HostView(s.width, s.height, s.maxDepth);
        view.samplesPerPixel = s.samplesPerPixel;
        view.tlas = {tlasNodes.Data(), instanceOrder.Data(), instances.Data(), blasViews.Data()};
        view.materials = materials.Data();
        view.lights = lights.Data();
        view.textures = textures.Data();
        view.texels = texels.Data();
        return view;
    }
};

}  // namespace rtrt
