#include "bench/accuracy/accuracy_scenes.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/bvh/tlas/dynamic_tlas.h"
#include "engine/bvh/tlas/tlas.h"
#include "game/scene/paper_scene.h"

namespace rtrt {
namespace {

std::shared_ptr<const Blas> GroundBlas(float groundY0) {
    TriangleMesh ground;
    const float h = kGroundHalfSize;
    for (vec2 c : {vec2(-h, -h), vec2(h, -h), vec2(h, h), vec2(-h, h)})
        ground.positions.push_back(vec3(c.x, GroundHeight(groundY0, c.x, c.y), c.y));
    ground.indices = {{0, 2, 1}, {0, 3, 2}};
    return std::make_shared<const Blas>(BuildTriangleBlas(ground));
}

}  // namespace

RenderScene MakeAccuracyDragonScene(std::shared_ptr<const Blas> dragon) {
    const float groundY0 = dragon->bounds.min.y - 0.01f;
    RenderScene scene = MakePaperScene(std::move(dragon));
    scene.maxDepth = 8;
    Material grey;
    grey.diffuse = vec3(0.6f);
    grey.ambient = vec3(0.06f);
    grey.specular = vec3(0.2f);
    grey.shininess = 16.0f;
    grey.reflectivity = 0.2f;
    scene.AddInstance(scene.AddBlas(GroundBlas(groundY0)), scene.AddMaterial(grey),
                      glm::mat4(1.0f));
    Material glass;
    glass.diffuse = vec3(0.0f);
    glass.ambient = vec3(0.0f);
    glass.specular = vec3(0.8f);
    glass.shininess = 128.0f;
    glass.transmissivity = 0.95f;
    glass.ior = 1.5f;
    const float radius = 1.2f, x = 3.6f, z = 1.5f;
    const Sphere sphere{vec3(x, GroundHeight(groundY0, x, z) + radius, z), radius};
    scene.AddInstance(scene.AddBlas(std::make_shared<const Blas>(BuildSphereBlas({&sphere, 1}))),
                      scene.AddMaterial(glass), glm::mat4(1.0f));
    scene.BuildTlas();
    return scene;
}

RenderScene MakeFarSpheresScene() {
    RenderScene scene;
    scene.camera = {vec3(0.0f), vec3(0, 0, -1), vec3(0, 1, 0), 0.3f};
    scene.background = vec3(0.2f, 0.3f, 0.5f);
    scene.maxDepth = 8;
    const Sphere unit{vec3(0.0f), 1.5f};
    const uint32_t blas = scene.AddBlas(std::make_shared<const Blas>(BuildSphereBlas({&unit, 1})));
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 7; ++col) {
            Material m;
            m.diffuse = vec3(0.2f + 0.1f * float(col), 0.6f, 0.2f + 0.2f * float(row));
            m.ambient = 0.1f * m.diffuse;
            m.specular = vec3(0.4f);
            m.reflectivity = 0.2f;
            const vec3 at(4.0f * (float(col) - 3.0f), 4.0f * (float(row) - 1.5f), -4000.0f);
            scene.AddInstance(blas, scene.AddMaterial(m), glm::translate(glm::mat4(1.0f), at));
        }
    }
    scene.lights.push_back({glm::normalize(vec3(1.0f)), LightType::kDirectional, vec3(1.0f), 0.0f});
    scene.BuildTlas();
    return scene;
}

void UseRuntimeTlas(RenderScene& scene, uint32_t frames) {
    std::vector<Aabb> blasBounds;
    for (const auto& blas : scene.blases) blasBounds.push_back(blas->bounds);
    std::vector<Instance> before = scene.instances;
    const size_t n = before.size();
    for (size_t i = 0; i < n; ++i) {
        const float angle = 2.39996f * float(i);  // the golden angle: directions spread evenly
        const vec3 step = kInstanceSpeed * vec3(std::cos(angle), std::sin(angle), 0.0f);
        for (int r = 0; r < 3; ++r)
            before[i].inverseAndPosition.row[r].w -= float(frames) * step[r];
    }
    // Never rebuilt by the SAH-growth rule: the interval alone decides.
    DynamicTlas tlas(TlasPolicy{false, 1e30f, 0});
    const std::vector<BlasOutline> outlines = scene.BlasOutlines();
    tlas.Update(before, blasBounds, true, outlines);
    if (frames > 0) tlas.Update(scene.instances, blasBounds, false, outlines);
    scene.SetTlas({tlas.Tree().nodes});
}

}  // namespace rtrt
