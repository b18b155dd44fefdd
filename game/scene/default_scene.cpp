#include "game/scene/default_scene.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/matrix_decompose.hpp>

#include "game/assets/procedural_shapes.h"

namespace rtrt {

RenderScene MakeDefaultScene() {
    RenderScene scene;
    scene.camera = {vec3(0.0f, 2.2f, 8.0f), vec3(0.0f, -0.25f, -1.0f), vec3(0, 1, 0), 45.0f};
    scene.background = vec3(0.2f, 0.3f, 0.5f);
    scene.maxDepth = 6;

    auto material = [&](vec3 diffuse, vec3 specular, float reflectivity, float transmissivity) {
        Material m;
        m.diffuse = diffuse;
        m.ambient = 0.1f * diffuse;
        m.specular = specular;
        m.shininess = 64.0f;
        m.reflectivity = reflectivity;
        m.transmissivity = transmissivity;
        m.ior = 1.5f;
        return scene.AddMaterial(m);
    };
    const uint32_t floorMaterial = material(vec3(0.75f), vec3(0.0f), 0.1f, 0.0f);
    const uint32_t mirror = material(vec3(0.9f), vec3(1.0f), 0.85f, 0.0f);
    const uint32_t glass = material(vec3(0.0f), vec3(1.0f), 0.0f, 0.95f);
    const uint32_t blue = material(vec3(0.15f, 0.3f, 0.85f), vec3(0.5f), 0.0f, 0.0f);
    const uint32_t red = material(vec3(0.85f, 0.15f, 0.1f), vec3(0.3f), 0.0f, 0.0f);

    const Sphere unit{vec3(0.0f), 1.0f};
    const uint32_t sphere = scene.AddBlas(
        std::make_shared<const Blas>(BuildSphereBlas(std::span<const Sphere>(&unit, 1))));
    const uint32_t floor =
        scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(MakePlaneMesh(40, 40))));
    const uint32_t box =
        scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(MakeBoxMesh(vec3(1.0f)))));

    const glm::mat4 identity(1.0f);
    scene.AddInstance(floor, floorMaterial, identity);
    scene.AddInstance(sphere, mirror, glm::translate(identity, vec3(-2.2f, 1.0f, -1.0f)));
    scene.AddInstance(sphere, glass, glm::translate(identity, vec3(0.3f, 1.0f, 1.2f)));
    scene.AddInstance(sphere, blue,
                      glm::scale(glm::translate(identity, vec3(2.4f, 0.7f, -0.5f)), vec3(0.7f)));
    scene.AddInstance(box, red,
                      glm::scale(glm::rotate(glm::translate(identity, vec3(0.2f, 0.75f, -3.0f)),
                                             glm::radians(30.0f), vec3(0, 1, 0)),
                                 vec3(1.5f)));

    scene.lights.push_back(
        {glm::normalize(vec3(-1.0f, 2.0f, 1.5f)), LightType::kDirectional, vec3(0.8f), 0.0f});
    scene.lights.push_back({vec3(3.0f, 4.0f, 3.0f), LightType::kPoint, vec3(0.35f), 0.0f});
    scene.BuildTlas();
    return scene;
}

LoadedScene MakeDefaultLoadedScene() {
    LoadedScene out;
    out.scene = MakeDefaultScene();
    for (uint32_t i = 0; i < out.scene.instances.size(); ++i) {
        const Instance& inst = out.scene.instances[i];
        EntityDesc d;
        d.blasId = inst.blasId;
        d.materialId = inst.materialId;
        d.sourceIndex = i;
        vec3 skew;
        vec4 perspective;
        glm::decompose(ObjectToWorldMatrix(inst), d.local.scale, d.local.rotation,
                       d.local.translation, skew, perspective);
        out.entities.push_back(d);
    }
    for (const auto& blas : out.scene.blases)
        out.modelNames.push_back(blas->kind == GeometryKind::kSpheres ? "sphere" : "mesh");
    // In MakeDefaultScene's order.
    out.materialNames = {"floor", "mirror", "glass", "blue", "red"};
    out.scene.instances.clear();
    FinishLoadedScene(out, "default");
    return out;
}

}  // namespace rtrt
