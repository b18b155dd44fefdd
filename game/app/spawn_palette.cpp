#include "game/app/spawn_palette.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "engine/physics_anim/animator.h"
#include "engine/physics_anim/skinning.h"
#include "game/assets/mesh_io.h"
#include "game/assets/model_dir.h"
#include "game/assets/procedural_shapes.h"
#include "game/assets/teapot.h"
#include "game/gltf/gltf_import.h"

namespace rtrt {
namespace {

Material Colored(vec3 diffuse, float reflectivity = 0.0f) {
    Material m;
    m.diffuse = diffuse;
    m.ambient = 0.1f * diffuse;
    m.specular = vec3(0.5f);
    m.shininess = 48.0f;
    m.reflectivity = reflectivity;
    return m;
}

std::shared_ptr<const Blas> FittedMeshBlas(TriangleMesh mesh) {
    FitMesh(mesh, 1.0f);
    return std::make_shared<const Blas>(BuildTriangleBlas(mesh));
}

// A box about the model's origin that holds it (FitMesh centres it): a sphere of the largest
// half extent left a flat model resting above the ground (the teapot 0.2 too high).
physics::Collider BoxAround(const Blas& blas) {
    return physics::Collider::Box(glm::max(glm::abs(blas.bounds.min), glm::abs(blas.bounds.max)));
}

// Whether E's object moves on its own: a dynamic body, a character's skinned mesh, or an object
// with an animator on it or its root.
bool Moves(const World& world, ecs::Entity e) {
    const ecs::Registry& registry = world.Registry();
    if (const physics::RigidBody* body = registry.Get<physics::RigidBody>(e))
        if (body->mass > 0.0f) return true;
    const ecs::Entity root = world.ObjectRoot(e);
    return registry.Has<physics::Skin>(e) || registry.Has<physics::Animator>(e) ||
           (!root.IsNull() && registry.Has<physics::Animator>(root));
}

// The distance along RAY to its nearest hit on something that stays put.
std::optional<float> PickStill(const World& world, Ray ray, const ScenePick& pick) {
    float travelled = 0.0f;
    for (int passed = 0; passed < 64; ++passed) {
        SceneHit hit{};
        if (!pick(ray, &hit)) return std::nullopt;
        if (!Moves(world, world.EntityOfInstance(hit.instance))) return travelled + hit.t;
        const float step = hit.t + 1e-4f * (1.0f + hit.t);  // on past the moving thing
        ray.origin += step * ray.dir;
        ray.tMax -= step;
        travelled += step;
        if (!(ray.tMax > 0.0f)) return std::nullopt;
    }
    return std::nullopt;
}

}  // namespace

std::optional<vec3> SpawnGround(const World& world, const Camera& camera, float distance,
                                const ScenePick& pick) {
    constexpr float kReach = 1000.0f, kAhead = 2.0f;
    const vec3 forward = glm::normalize(camera.forward);
    vec3 above = camera.position + distance * forward;
    if (const std::optional<float> t =
            PickStill(world, Ray{camera.position, kReach, forward, 0.0f}, pick))
        above = camera.position + std::max(*t - 0.5f, 0.0f) * forward;
    // Across the ground, ahead as the view looks (its up vector when it looks straight down).
    vec3 across(forward.x, 0.0f, forward.z);
    if (glm::length(across) < 1e-3f) across = vec3(camera.up.x, 0.0f, camera.up.z);
    if (glm::length(across) > 1e-6f) {
        across = glm::normalize(across);
        const vec3 offset = above - camera.position;
        if (glm::dot(vec3(offset.x, 0.0f, offset.z), across) < kAhead)
            above = camera.position + kAhead * across;
    }
    const std::optional<float> drop =
        PickStill(world, Ray{above, kReach, vec3(0.0f, -1.0f, 0.0f), 0.0f}, pick);
    if (!drop) return std::nullopt;
    return above - vec3(0.0f, *drop, 0.0f);
}

SpawnPalette::SpawnPalette(World& world, std::vector<std::string>* notes) {
    const Sphere unitSphere{vec3(0.0f), 0.5f};
    const uint32_t sphere =
        world.AddBlas(std::make_shared<const Blas>(BuildSphereBlas({&unitSphere, 1})));
    kinds_.push_back({"sphere", sphere, world.AddMaterial(Colored(vec3(0.85f, 0.25f, 0.2f), 0.1f)),
                      physics::Collider::Sphere(0.5f)});

    const std::string teapot = ModelDir() + "/teapot.inc";
    if (std::filesystem::exists(teapot)) {
        const std::shared_ptr<const Blas> blas = FittedMeshBlas(TessellateTeapot(teapot, 6));
        kinds_.push_back({"teapot", world.AddBlas(blas),
                          world.AddMaterial(Colored(vec3(0.9f, 0.7f, 0.2f))), BoxAround(*blas)});
    } else if (notes) {
        notes->push_back("no teapot to spawn: run tools/fetch_models.sh");
    }
    const std::string dragon = ModelDir() + "/dragon_vrip_res4.ply.gz";
    if (std::filesystem::exists(dragon)) {
        const std::shared_ptr<const Blas> blas = FittedMeshBlas(LoadMesh(dragon));
        kinds_.push_back({"dragon", world.AddBlas(blas),
                          world.AddMaterial(Colored(vec3(0.2f, 0.7f, 0.3f), 0.2f)),
                          BoxAround(*blas)});
    } else if (notes) {
        notes->push_back("no dragon to spawn: run tools/fetch_models.sh");
    }
    Material glass;
    glass.diffuse = vec3(0.0f);
    glass.ambient = vec3(0.0f);
    glass.specular = vec3(0.8f);
    glass.shininess = 200.0f;
    glass.transmissivity = 0.95f;
    glass.ior = 1.5f;
    kinds_.push_back(
        {"glass sphere", sphere, world.AddMaterial(glass), physics::Collider::Sphere(0.5f)});
    const uint32_t box =
        world.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(MakeBoxMesh(vec3(1.0f)))));
    kinds_.push_back({"mirror box", box, world.AddMaterial(Colored(vec3(0.1f), 0.9f)),
                      physics::Collider::Box(vec3(0.5f))});
    AddGltf(world, "walker", AssetDir() + "/models/walker.gltf", notes);
}

// The glTF file is read into a scene description that starts as a copy of the world's arrays,
// so the ids it hands out are the ones its models, materials and meshes get in the world.
void SpawnPalette::AddGltf(World& world, const std::string& name, const std::string& path,
                           std::vector<std::string>* notes) {
    if (!std::filesystem::exists(path)) {
        if (notes) notes->push_back("no " + name + " to spawn: " + path + " is missing");
        return;
    }
    const RenderScene& scene = world.Scene();
    LoadedScene into;
    into.scene.blases = scene.blases;
    into.scene.materials = scene.materials;
    into.scene.pbrMaterials = scene.pbrMaterials;
    into.scene.textures = scene.textures;
    into.scene.texels = scene.texels;
    into.scene.deformableMeshes = scene.deformableMeshes;
    auto asset = std::make_shared<GltfAsset>(LoadGltfAsset(path, into));
    for (size_t i = scene.blases.size(); i < into.scene.blases.size(); ++i)
        world.AddBlas(into.scene.blases[i]);
    for (size_t i = scene.materials.size(); i < into.scene.materials.size(); ++i)
        if (const Material& m = into.scene.materials[i]; m.pbrMaterial != kNoPbrMaterial)
            world.AddPbrMaterial(m, into.scene.pbrMaterials[m.pbrMaterial]);
        else
            world.AddMaterial(m);
    for (size_t i = scene.textures.size(); i < into.scene.textures.size(); ++i)
        world.AddTexture(into.scene.textures[i],
                         into.scene.texels.data() + into.scene.textures[i].texelOffset);
    for (size_t i = scene.deformableMeshes.size(); i < into.scene.deformableMeshes.size(); ++i)
        world.AddDeformableMesh(into.scene.deformableMeshes[i]);
    SpawnKind kind;
    kind.name = name;
    kind.gltf = std::move(asset);
    kinds_.push_back(std::move(kind));
}

const SpawnKind* SpawnPalette::Find(const std::string& name) const {
    for (const SpawnKind& k : kinds_)
        if (k.name == name) return &k;
    return nullptr;
}

ecs::Entity SpawnPalette::SpawnInFront(World& world, const SpawnKind& kind, const Camera& camera,
                                       float distance, const vec3* ground) const {
    const vec3 forward = glm::normalize(camera.forward);
    if (kind.gltf) {
        // Standing on the ground found ahead, else on y = 0 under the point ahead, turned to
        // face the camera.
        vec3 at = camera.position + distance * forward;
        at.y = 0.0f;
        if (ground) at = *ground;
        LoadedScene group;
        group.scene.deformableMeshes = world.Scene().deformableMeshes;  // what it places reads
        EntityDesc root;
        root.renderable = false;
        root.local.translation = at;
        const vec3 back = camera.position - at;
        root.local.rotation = glm::angleAxis(std::atan2(back.x, back.z), vec3(0, 1, 0));
        group.entities.push_back(root);
        // Copies walk out of step: phases a golden-ratio fraction of a second apart.
        const double phase = std::fmod(0.6180339887498949 * double(spawnedGltf_++), 1.0);
        InstantiateGltf(*kind.gltf, group, 0, physics::ToMatrix(root.local), phase);
        return world.SpawnGroup(group.entities);
    }
    EntityDesc desc;
    desc.blasId = kind.blasId;
    desc.materialId = kind.materialId;
    desc.local.translation = camera.position + distance * forward;
    desc.local.scale = vec3(kind.scale);
    if (world.HasPhysics()) {
        physics::RigidBody body;
        body.mass = 1.0f;
        body.velocity = kThrowSpeed * forward;
        desc.body = body;
        desc.collider = kind.collider;
    }
    return world.Spawn(desc);
}

}  // namespace rtrt
