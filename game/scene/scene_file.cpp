#include "game/scene/scene_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <initializer_list>
#include <map>
#include <memory>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/render_rt/camera.h"
#include "game/assets/model_dir.h"
#include "game/gltf/gltf_import.h"
#include "game/scene/default_scene.h"
#include "game/scene/json_fields.h"
#include "game/scene/scene_animation.h"
#include "game/scene/scene_camera_path.h"
#include "game/scene/scene_deform.h"
#include "game/scene/scene_models.h"
#include "game/scene/scene_rigid_body.h"
#include "game/scene/spawn_places.h"

namespace rtrt {
namespace {

class SceneParser {
  public:
    SceneParser(std::string name, std::string baseDir)
        : file_(std::move(name)), baseDir_(std::move(baseDir)) {}

    LoadedScene Parse(const std::string& text) {
        const Json root = ParseJson(text, file_);
        JsonFields top(root, "", file_);
        LoadedScene out;
        out_ = &out;
        RenderScene& scene = out.scene;
        hasCamera_ = top.Has("camera");
        if (hasCamera_) scene.camera = ParseCamera(top.Get("camera"), top.Has("camera_path"));
        scene.background = top.Colour("background", scene.background);
        scene.maxDepth = top.Count("max_depth", 1, 16, scene.maxDepth);
        out.output = ParseOutputTransform(top);
        if (top.Has("image")) {
            JsonFields image(top.Get("image"), "image", file_);
            out.width = image.Count("width", 1, 16384, 1280);
            out.height = image.Count("height", 1, 16384, 720);
            image.Finish();
        }
        if (top.Has("materials")) ParseMaterials(top.Get("materials"), scene);
        if (top.Has("lights")) ParseLights(top.Get("lights"), scene);
        if (top.Has("models")) ParseModels(top.Get("models"), scene);
        ParseInstances(top.Get("instances"), out);
        if (top.Has("spawners")) ParseSpawners(top.Get("spawners"), out);
        if (top.Has("camera_path"))
            out.cameraPath = ParseCameraPath(top.Get("camera_path"), scene.camera.up, file_);
        top.Finish();
        // A scene of display colours uses its glTF models' textures as they are, as it always has.
        if (!out.output.srgbEncode)
            for (Texture& t : scene.textures) t.srgb = 0;
        CheckRigidBodiesHaveRoom(out, file_);
        FinishLoadedScene(out, file_);
        return out;
    }

  private:
    // "colours": "display" (the default: colours are what the image shows, clamped) or "linear"
    // (linear light, with "exposure" in EV and a "tone_map", then sRGB for 8-bit outputs).
    OutputTransform ParseOutputTransform(JsonFields& top) {
        const std::string colours = top.String("colours", "display");
        if (colours != "display" && colours != "linear")
            top.Fail("colours", "expected \"display\" or \"linear\", got \"" + colours + "\"");
        if (colours == "display") {
            for (const char* key : {"exposure", "tone_map"})
                if (top.Has(key))
                    top.Fail(key, "applies to linear colours: add \"colours\": \"linear\"");
            return kDisplayValues;
        }
        OutputTransform t = kLinearToSrgb;
        t.exposureEv = top.InRange("exposure", -20.0f, 20.0f, 0.0f);
        const std::string toneMap = top.String("tone_map", "pbr_neutral");
        if (!ParseToneMap(toneMap.c_str(), &t.toneMap))
            top.Fail("tone_map", "expected pbr_neutral, aces or clamp, got \"" + toneMap + "\"");
        return t;
    }

    // With a camera path, which gives every view, a camera that names no view of its own gives
    // only its up and field of view.
    Camera ParseCamera(const Json& j, bool path) {
        JsonFields f(j, "camera", file_);
        Camera c;
        c.position = f.Position("position", c.position);
        if (f.Has("look_at") && f.Has("forward"))
            f.Fail("look_at", "give either look_at or forward, not both");
        if (f.Has("look_at"))
            c.forward = f.Vec3("look_at") - c.position;
        else
            c.forward = f.Vec3("forward", c.forward);
        c.up = f.Vec3("up", c.up);
        c.fovYDegrees = f.InRange("fov_y", 1.0f, 179.0f, c.fovYDegrees);
        const std::string view = f.Has("look_at") ? "look_at" : "forward";
        if (!IsFinite(c.forward))
            f.Fail(view,
                   "the view direction is beyond float's range (look_at too far from position)");
        if (c.forward == vec3(0.0f)) f.Fail(view, "the view direction has zero length");
        const bool ownView = f.Has("look_at") || f.Has("forward") || !path;
        if (ownView && !CameraBasisDefined(c.forward, c.up))
            f.Fail("up", "up must not be parallel to the view direction (or zero)");
        if (!ownView && (!IsFinite(c.up) || c.up == vec3(0.0f)))
            f.Fail("up", "up must be a finite, non-zero direction");
        c.forward = ScaledForNormalize(c.forward);
        c.up = ScaledForNormalize(c.up);
        f.Finish();
        return c;
    }

    void ParseMaterials(const Json& j, RenderScene& scene) {
        if (!j.is_object())
            throw InputError(
                file_, "materials",
                std::string("expected an object of named materials, got ") + j.type_name());
        for (const auto& [name, value] : j.items()) {
            JsonFields f(value, "materials." + name, file_);
            Material m;
            m.diffuse = f.Colour("diffuse", m.diffuse);
            m.ambient = f.Colour("ambient", 0.1f * m.diffuse);
            m.specular = f.Colour("specular", m.specular);
            m.shininess = f.InRange("shininess", 0.0f, 1e6f, m.shininess);
            m.reflectivity = f.InRange("reflectivity", 0.0f, 1.0f, m.reflectivity);
            m.transmissivity = f.InRange("transmissivity", 0.0f, 1.0f, m.transmissivity);
            m.ior = f.InRange("ior", 1.0f, 10.0f, m.ior);
            if (m.reflectivity + m.transmissivity > 1.0f)
                f.Fail("transmissivity", "reflectivity + transmissivity must not exceed 1");
            f.Finish();
            materialIds_[name] = scene.AddMaterial(m);
            out_->materialNames.push_back(name);
        }
    }

    // "falloff": "none" (the default: the colour at every distance, as rtrt's lights always
    // were) or "inverse_square" (colour / distance^2, to nothing at "range" if given).
    static void ParseFalloff(JsonFields& f, Light* light) {
        const std::string falloff = f.String("falloff", std::string("none"));
        if (falloff == "inverse_square") {
            light->falloff = 1;
            // 0 is the light's own "no range"; given, a range must be one.
            if (f.Has("range")) {
                light->range = f.Positive("range");
                if (!(light->range <= 1e30f)) f.Fail("range", "must be at most 1e30");
            }
        } else if (falloff != "none") {
            f.Fail("falloff",
                   "unknown falloff \"" + falloff + "\" (expected none or inverse_square)");
        }
    }

    void ParseLights(const Json& j, RenderScene& scene) {
        if (!j.is_array())
            throw InputError(file_, "lights",
                             std::string("expected an array, got ") + j.type_name());
        for (size_t i = 0; i < j.size(); ++i) {
            JsonFields f(j[i], JsonIndexed("lights", i), file_);
            Light light;
            const std::string type = f.String("type");
            if (type == "directional") {
                light.type = LightType::kDirectional;
                const vec3 d = f.Vec3("direction");
                if (d == vec3(0.0f)) f.Fail("direction", "direction has zero length");
                light.vector = glm::normalize(ScaledForNormalize(d));
            } else if (type == "point" || type == "spot") {
                light.type = type == "point" ? LightType::kPoint : LightType::kSpot;
                light.vector = f.Position("position");
                ParseFalloff(f, &light);
                if (type == "spot") {
                    const vec3 d = f.Vec3("direction");
                    if (d == vec3(0.0f)) f.Fail("direction", "direction has zero length");
                    light.spotAxis = glm::normalize(ScaledForNormalize(d));
                    const float outer = f.InRange("outer_cone", 0.1f, 90.0f, 45.0f);
                    const float inner = f.InRange("inner_cone", 0.0f, outer, 0.0f);
                    if (inner >= outer)
                        f.Fail("inner_cone", "must be less than outer_cone (" +
                                                 std::to_string(outer) + " degrees)");
                    SetSpotCone(&light, inner * kPi / 180.0f, outer * kPi / 180.0f);
                }
            } else {
                f.Fail("type",
                       "unknown light type \"" + type + "\" (expected directional, point or spot)");
            }
            light.color = f.Colour("color", vec3(1.0f));
            f.Finish();
            scene.lights.push_back(light);
        }
    }

    void ParseModels(const Json& j, RenderScene& scene) {
        if (!j.is_object())
            throw InputError(
                file_, "models",
                std::string("expected an object of named models, got ") + j.type_name());
        for (const auto& [name, value] : j.items()) {
            JsonFields f(value, "models." + name, file_);
            if (value.contains("type") && value["type"] == "gltf") {
                // A glTF scene: its meshes, materials and textures are added once here; every
                // instance places its node hierarchy again.
                f.String("type");
                const std::string spec = f.String("file");
                if (const std::string missing = MissingModelReason(spec, baseDir_);
                    !missing.empty())
                    f.Fail("file", missing);
                const std::string path = ResolveModelPath(spec, baseDir_);
                f.Finish();
                gltfAssets_[name] = std::make_shared<GltfAsset>(LoadGltfAsset(path, *out_));
                out_->gltfFiles.push_back(gltfAssets_[name]->summary);
                continue;
            }
            ModelShape shape;
            modelIds_[name] =
                scene.AddBlas(std::make_shared<const Blas>(ParseSceneModel(f, baseDir_, shape)));
            modelShapes_[modelIds_[name]] = shape;
            modelNames_[modelIds_[name]] = name;
            out_->modelNames.push_back(name);
            f.Finish();
        }
    }

    void ParseInstances(const Json& j, LoadedScene& out) {
        if (!j.is_array())
            throw InputError(file_, "instances",
                             std::string("expected an array, got ") + j.type_name());
        for (size_t i = 0; i < j.size(); ++i) {
            JsonFields f(j[i], JsonIndexed("instances", i), file_);
            Reserve(f, "", 1);
            out.entities.push_back(ParseEntity(f, out.scene));
            out.entities.back().sourceIndex = uint32_t(i);
            // A glTF instance may start its file's animation this many seconds in (bounded as
            // the scene's other times are, so that a frame's step still moves the clock).
            const float phase = gltf_ ? f.InRange("phase", -1e6f, 1e6f, 0.0f) : 0.0f;
            f.Finish();
            if (!gltf_) continue;
            // The instance is the root the glTF scene's nodes hang from; its entities are
            // counted before they are made (10 million from a 950 KB file ran out of memory).
            Reserve(f, "model", GltfEntityCount(*gltf_));
            const std::optional<Camera> camera =
                InstantiateGltf(*gltf_, out, int32_t(out.entities.size() - 1),
                                StartWorld(out.entities.back()), phase);
            if (camera && !hasCamera_) {
                out.scene.camera = *camera;
                hasCamera_ = true;
            }
        }
    }

    // The fields an instance and a spawner share: model, material, pose, animation, rigid body.
    EntityDesc ParseEntity(JsonFields& f, RenderScene& scene) {
        EntityDesc e;
        const std::string model = f.String("model");
        auto gltf = gltfAssets_.find(model);
        gltf_ = gltf == gltfAssets_.end() ? nullptr : gltf->second.get();
        if (gltf_) {
            if (f.Has("material")) f.Fail("material", "a glTF model brings its own materials");
            if (f.Has("rigid_body")) f.Fail("rigid_body", "a glTF model cannot be a rigid body");
            if (f.Has("deform"))
                f.Fail("deform", "a glTF model deforms by its own skins and morph targets");
            e.renderable = false;
            e.local = ParseTransform(f);
            if (f.Has("animate"))
                e.animator = ParseAnimator(f.Get("animate"), f.Path("animate"), e.local, file_);
            return e;
        }
        auto modelIt = modelIds_.find(model);
        if (modelIt == modelIds_.end())
            f.Fail("model", "no model named \"" + model + "\" in models");
        e.blasId = modelIt->second;
        if (f.Has("material")) {
            const std::string name = f.String("material");
            auto it = materialIds_.find(name);
            if (it == materialIds_.end())
                f.Fail("material", "no material named \"" + name + "\" in materials");
            e.materialId = it->second;
        } else {
            if (defaultMaterial_ == UINT32_MAX) defaultMaterial_ = scene.AddMaterial(Material{});
            e.materialId = defaultMaterial_;
        }
        e.local = ParseTransform(f);
        if (f.Has("animate"))
            e.animator = ParseAnimator(f.Get("animate"), f.Path("animate"), e.local, file_);
        if (f.Has("rigid_body")) {
            if (e.animator)
                f.Fail("rigid_body", "an entity is either animated or simulated, not both");
            ParseRigidBody(f.Get("rigid_body"), f.Path("rigid_body"), file_, modelShapes_[e.blasId],
                           modelNames_[e.blasId], e);
        }
        if (f.Has("deform")) {
            const Blas& blas = *scene.blases[e.blasId];
            if (blas.kind != GeometryKind::kTriangles)
                f.Fail("deform", "model \"" + model + "\" is not a triangle mesh");
            if (e.body) f.Fail("deform", "a rigid body cannot deform");
            e.procedural = ParseDeform(f.Get("deform"), f.Path("deform"), blas.bounds, file_);
            e.deformableMesh = int32_t(DeformableMeshOf(e.blasId, scene));
        }
        return e;
    }

    // The rest mesh of a model that deforms, made once however many instances deform it.
    uint32_t DeformableMeshOf(uint32_t blasId, RenderScene& scene) {
        auto known = deformableMeshes_.find(blasId);
        if (known != deformableMeshes_.end()) return known->second;
        const uint32_t id = scene.AddDeformableMesh(
            std::make_shared<const DeformableMesh>(RestMeshOfBlas(*scene.blases[blasId])));
        deformableMeshes_[blasId] = id;
        return id;
    }

    // Spawners place many copies of one entity: on a grid, or as a rain at random (seeded)
    // places in a region, at a given time.
    void ParseSpawners(const Json& j, LoadedScene& out) {
        if (!j.is_array())
            throw InputError(file_, "spawners",
                             std::string("expected an array, got ") + j.type_name());
        uint32_t rains = 0;
        for (size_t i = 0; i < j.size(); ++i) {
            JsonFields f(j[i], JsonIndexed("spawners", i), file_);
            EntityDesc proto = ParseEntity(f, out.scene);
            proto.spawnTime = f.InRange("time", 0.0f, 1e6f, 0.0f);
            if (gltf_) {
                SpawnGltfGrid(f, proto, uint32_t(i), out);
                f.Finish();
                continue;
            }
            const bool grid = f.Has("grid"), rain = f.Has("rain");
            if (grid == rain) f.Fail("", "give exactly one of grid or rain");
            const std::vector<vec3> places =
                grid ? GridPlaces(f, proto.local.translation, file_)
                     // Rains that give no seed each get their own (the first keeps 1): with one
                     // default, two rains over one region put every body of one inside another.
                     : RainPlaces(f, BodyRadius(proto, out.scene), ++rains, file_);
            Reserve(f, grid ? "grid.count" : "rain.count", places.size());
            if (proto.body) CheckRigidBodyPlaces(f, grid ? "grid" : "rain", places);
            proto.sourceArray = "spawners";
            proto.sourceIndex = uint32_t(i);
            for (const vec3& p : places) {
                out.entities.push_back(proto);
                PlaceCopy(out.entities.back(), p);
            }
            f.Finish();
        }
    }

    // A grid of a glTF scene: each place is a root entity its nodes hang from, playing the file's
    // animation in a phase of its own — "phase" seconds, plus "phase_spread" x a low-discrepancy
    // fraction of the place (the golden ratio's multiples), so a crowd does not march in step.
    void SpawnGltfGrid(JsonFields& f, const EntityDesc& proto, uint32_t index, LoadedScene& out) {
        if (f.Has("rain")) f.Fail("rain", "a glTF scene is spawned on a grid, not by rain");
        if (!f.Has("grid")) f.Fail("grid", "a glTF scene is spawned on a grid: give one");
        if (proto.spawnTime != 0.0f) f.Fail("time", "a glTF grid is placed at time 0");
        const float phase = f.InRange("phase", -1e6f, 1e6f, 0.0f);
        const float spread = f.InRange("phase_spread", 0.0f, 1e6f, 0.0f);
        const std::vector<vec3> places = GridPlaces(f, proto.local.translation, file_);
        if (places.size() > 100000) f.Fail("grid.count", "at most 100,000 places of a glTF scene");
        size_t perPlace = 0;  // the root and its nodes' entities, found by the first place
        for (size_t k = 0; k < places.size(); ++k) {
            Reserve(f, "grid.count", perPlace * (places.size() - k));
            const size_t before = out.entities.size();
            EntityDesc root = proto;
            root.sourceArray = "spawners";
            root.sourceIndex = index;
            PlaceCopy(root, places[k]);
            out.entities.push_back(root);
            const double golden = 0.6180339887498949;
            const double fraction = std::fmod(double(k) * golden, 1.0);
            const std::optional<Camera> camera =
                InstantiateGltf(*gltf_, out, int32_t(out.entities.size() - 1), StartWorld(root),
                                double(phase) + double(spread) * fraction);
            // The first place's camera, as an instance of the file would give it.
            if (camera && !hasCamera_) {
                out.scene.camera = *camera;
                hasCamera_ = true;
            }
            perPlace = out.entities.size() - before;
        }
    }

    // A spawner's copy moved from the spawner's position to place p: its pose, and its animation
    // with it (translation keys and an orbit's centre are authored about the spawner's position).
    static void PlaceCopy(EntityDesc& e, vec3 p) {
        const vec3 offset = p - e.local.translation;
        e.local.translation = p;
        if (!e.animator) return;
        e.animator->base.translation = p;
        e.animator->keyOffset += offset;
        for (physics::ProceduralMotion& m : e.animator->motions)
            if (auto* orbit = std::get_if<physics::Orbit>(&m)) orbit->centre += offset;
    }

    // Where an entity's world starts: its animation's first pose where it has one (the pose
    // FinishLoadedScene gives it), else its position. A glTF file's lights and cameras are
    // placed from it.
    static glm::mat4 StartWorld(const EntityDesc& e) {
        return physics::ToMatrix(e.animator ? physics::EvaluateAnimator(*e.animator) : e.local);
    }

    // The radius of a ball about the entity's model that a rain keeps apart: the sphere's own for a
    // sphere model, half the scaled box's diagonal for any other.
    float BodyRadius(const EntityDesc& proto, const RenderScene& scene) const {
        const Aabb bounds = scene.blases[proto.blasId]->bounds;
        const ModelShape& shape = modelShapes_.at(proto.blasId);
        return shape.kind == ModelShape::kSphere
                   ? shape.radius * MaxComponent(proto.local.scale)
                   : 0.5f * glm::length(bounds.Extent() * proto.local.scale);
    }

    // Fails on field of f when `more` entities on top of those made so far would exceed the
    // scene's budget.
    void Reserve(const JsonFields& f, const std::string& field, uint64_t more) const {
        const uint64_t total = out_->entities.size() + more;
        if (total <= kMaxSceneEntities) return;
        f.Fail(field, "the scene would have " + std::to_string(total) +
                          " entities or more; a scene may have at most 2,000,000");
    }

    // position * rotation (degrees about x, then y, then z) * scale.
    physics::LocalTransform ParseTransform(JsonFields& f) {
        const vec3 position = f.Position("position", vec3(0.0f));
        const vec3 rotation = f.Vec3("rotation", vec3(0.0f));
        vec3 scale(1.0f);
        if (f.Has("scale")) {
            const Json& value = f.Get("scale");
            if (value.is_number()) {
                scale = vec3(f.Positive("scale"));
            } else if (value.is_array()) {
                scale = f.Vec3("scale");
            } else {
                f.Fail("scale", std::string("expected a number or an array of 3 numbers, got ") +
                                    value.type_name());
            }
            if (!(scale.x > 0 && scale.y > 0 && scale.z > 0))
                f.Fail("scale", "scale factors must be greater than 0");
            // As models' own sizes are bounded (scene_models.cpp): a sphere scaled by 1e15
            // vanished.
            if (!(std::max({scale.x, scale.y, scale.z}) <= 1e6f))
                f.Fail("scale", "scale factors must be at most 1e6");
            // Flattened more than 1e-4 of its other sides, a model's error bounds (taken in its
            // own space, where it is not flat) no longer keep secondary rays off its surface: a
            // box scaled by 1e-6 in z shadowed its own lit face. A uniform scale is free.
            if (!(std::min({scale.x, scale.y, scale.z}) >=
                  1e-4f * std::max({scale.x, scale.y, scale.z})))
                f.Fail("scale",
                       "the smallest scale factor must be at least 1e-4 of the largest (size the "
                       "model instead)");
        }
        physics::LocalTransform t;
        t.translation = position;
        t.rotation = EulerDegrees(rotation);
        t.scale = scale;
        return t;
    }

    std::string file_, baseDir_;
    std::map<std::string, uint32_t> materialIds_, modelIds_;
    std::map<uint32_t, ModelShape> modelShapes_;
    std::map<uint32_t, std::string> modelNames_;
    std::map<uint32_t, uint32_t> deformableMeshes_;  // BLAS id -> its rest mesh, once deformed
    std::map<std::string, std::shared_ptr<const GltfAsset>> gltfAssets_;
    const GltfAsset* gltf_ = nullptr;  // the glTF model of the entity just parsed, if it is one
    bool hasCamera_ = false;           // the file or an included glTF has set the camera
    LoadedScene* out_ = nullptr;       // the scene being parsed
    uint32_t defaultMaterial_ = UINT32_MAX;
};

}  // namespace

LoadedScene ParseScene(const std::string& text, const std::string& name,
                       const std::string& baseDir) {
    return SceneParser(name, baseDir).Parse(text);
}

namespace {

// The scene file a bare NAME (or NAME.json) means in the project's scenes folder, or empty.
std::string SceneByName(const std::string& name) {
    if (name.empty() || name.find('/') != std::string::npos) return {};
    std::error_code ec;
    const std::filesystem::path dir = std::filesystem::path(AssetDir()) / "scenes";
    for (const std::string& candidate : {name, name + ".json"})
        if (std::filesystem::is_regular_file(dir / candidate, ec))
            return (dir / candidate).string();
    // rtrt's own glTF models (walker, pbr_showcase...), which an installed rtrt keeps in
    // share/rtrt/models.
    const std::filesystem::path models = std::filesystem::path(AssetDir()) / "models";
    for (const std::string& candidate : {name + ".gltf", name + ".glb"})
        if (std::filesystem::is_regular_file(models / candidate, ec))
            return (models / candidate).string();
    return {};
}

// The sorted stems of the files in AssetDir()/FOLDER with one of EXTENSIONS.
std::vector<std::string> AssetNames(const char* folder,
                                    std::initializer_list<const char*> extensions) {
    std::error_code ec;
    std::vector<std::string> names;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::path(AssetDir()) / folder, ec))
        for (const char* extension : extensions)
            if (entry.path().extension() == extension)
                names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

// " (scenes by name: a, b, ...; glTF models: c, d)" for a bare name, so that a user sees what
// exists.
std::string SceneNamesHint(const std::string& name) {
    if (name.find('/') != std::string::npos) return {};
    const std::vector<std::string> scenes = AssetNames("scenes", {".json"});
    if (scenes.empty()) return {};
    std::string hint = " (scenes by name:";
    for (size_t i = 0; i < scenes.size(); ++i) hint += (i ? ", " : " ") + scenes[i];
    const std::vector<std::string> models = AssetNames("models", {".gltf", ".glb"});
    for (size_t i = 0; i < models.size(); ++i) hint += (i ? ", " : "; glTF models: ") + models[i];
    return hint + ")";
}

}  // namespace

std::string ScenePathFor(const std::string& argument) {
    std::error_code ec;
    if (std::filesystem::exists(argument, ec)) return argument;
    const std::string known = SceneByName(argument);
    return known.empty() ? argument : known;
}

LoadedScene LoadSceneFile(const std::string& path) {
    if (IsGltfPath(path)) return LoadGltfScene(path);
    std::error_code ec;
    if (path == "default" && !std::filesystem::exists(path, ec)) return MakeDefaultLoadedScene();
    if (!std::filesystem::exists(path, ec)) {
        // A bare name is looked for among the project's scenes (installed or in the tree).
        const std::string known = SceneByName(path);
        if (known.empty()) throw InputError(path, "", "no such file" + SceneNamesHint(path));
        return LoadSceneFile(known);
    }
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, "", "is a directory, not a scene file");
    const std::string text = ReadAssetFile(path);
    const std::string dir = std::filesystem::path(path).parent_path().string();
    return ParseScene(text, path, dir);
}

}  // namespace rtrt
