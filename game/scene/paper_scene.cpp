#include "game/scene/paper_scene.h"

namespace rtrt {

RenderScene MakePaperScene(std::shared_ptr<const Blas> blas) {
    RenderScene scene;
    scene.camera = {vec3(0, 0, 10), vec3(0, 0, -1), vec3(0, 1, 0), 45.0f};
    scene.background = vec3(0.2f, 0.3f, 0.5f);
    scene.maxDepth = kPaperMaxDepth;
    Material red;
    red.diffuse = vec3(0.8f, 0.1f, 0.1f);
    red.ambient = 0.1f * red.diffuse;
    red.specular = vec3(0.5f);
    red.shininess = 32.0f;
    red.reflectivity = 0.3f;
    const uint32_t material = scene.AddMaterial(red);
    scene.AddInstance(scene.AddBlas(std::move(blas)), material, glm::mat4(1.0f));
    scene.lights.push_back({glm::normalize(vec3(1.0f)), LightType::kDirectional, vec3(1.0f), 0.0f});
    scene.BuildTlas();
    return scene;
}

}  // namespace rtrt
