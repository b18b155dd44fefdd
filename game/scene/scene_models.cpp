#include "game/scene/scene_models.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include "game/assets/mesh_io.h"
#include "game/assets/model_cache.h"
#include "game/assets/model_dir.h"
#include "game/assets/procedural_shapes.h"
#include "game/assets/teapot.h"

namespace rtrt {
namespace {

// The largest sphere radius and centre coordinate, box side, plane side and fitted size a scene
// may give: the sphere test squares distances of this order, which must stay far inside float's
// range (a radius of 1e20 made NaN pixels), and the ray offsets that keep shadow rays off their
// surface grow with the scene (a plane of side 1e10 rendered as if in shadow, one of 1e15 not at
// all).
constexpr float kMaxModelExtent = 1e6f;

// "fit": the size the model is scaled to, greater than 0 and at most kMaxModelExtent, for a model
// whose triangles cover BOUNDS: one so small that the scale overflows is refused as such (its
// infinite world bounds had been put down to a model too large).
float FitSize(JsonFields& f, const Aabb& bounds) {
    const float fit = f.Positive("fit");
    if (!(fit <= kMaxModelExtent)) f.Fail("fit", "must be at most 1e6");
    const float largest = MaxComponent(bounds.Extent());
    if (!bounds.IsEmpty() && largest > 0.0f && !std::isfinite(fit / largest)) {
        char extent[32];
        std::snprintf(extent, sizeof(extent), "%g", double(largest));
        f.Fail("fit", std::string("the model's largest extent, ") + extent +
                          ", is too small to be scaled in 32-bit floats");
    }
    return fit;
}

std::vector<Sphere> ParseSphereList(JsonFields& f) {
    const Json& list = f.Get("spheres");
    if (!list.is_array() || list.empty())
        f.Fail("spheres", "expected a non-empty array of [x, y, z, radius]");
    std::vector<Sphere> spheres;
    for (size_t i = 0; i < list.size(); ++i) {
        const Json& s = list[i];
        const std::string key = "spheres[" + std::to_string(i) + "]";
        if (!s.is_array() || s.size() != 4) f.Fail(key, "expected [x, y, z, radius]");
        for (const Json& v : s)
            if (!v.is_number() || !std::isfinite(v.get<double>()))
                f.Fail(key, "expected finite numbers");
        if (!(s[3].get<float>() > 0.0f)) f.Fail(key, "radius must be greater than 0");
        for (size_t c = 0; c < 4; ++c)
            if (!(std::fabs(s[c].get<double>()) <= kMaxModelExtent))
                f.Fail(key, "centre coordinates and radius must be at most 1e6 in magnitude");
        spheres.push_back(
            {vec3(s[0].get<float>(), s[1].get<float>(), s[2].get<float>()), s[3].get<float>()});
    }
    return spheres;
}

// The model file a "file" field names (FALLBACK when absent), resolved; a fetched model that
// is missing fails here, naming the field and how to get it.
std::string ModelFile(JsonFields& f, std::optional<std::string> fallback,
                      const std::string& baseDir) {
    const std::string spec = f.String("file", fallback);
    if (const std::string missing = MissingModelReason(spec, baseDir); !missing.empty())
        f.Fail("file", missing);
    return ResolveModelPath(spec, baseDir);
}

}  // namespace

Blas ParseSceneModel(JsonFields& f, const std::string& baseDir, ModelShape& shape) {
    BvhBuildOptions options;
    const std::string builder = f.String("builder", "binned");
    if (!ParseBuilder(builder, &options.builder))
        f.Fail("builder",
               "unknown builder \"" + builder + "\" (expected binned, sweep, centroid or sbvh)");
    const std::string type = f.String("type");
    if (options.builder == BvhBuilder::kSpatialSah && (type == "sphere" || type == "spheres"))
        f.Fail("builder", "sbvh splits triangles; sphere models take binned, sweep or centroid");
    if (type == "sphere") {
        const Sphere s{vec3(0.0f), f.Positive("radius", 1.0f)};
        if (!(s.radius <= kMaxModelExtent)) f.Fail("radius", "must be at most 1e6");
        shape = {ModelShape::kSphere, s.radius, vec3(0.0f)};
        return BuildSphereBlas(std::span<const Sphere>(&s, 1), options);
    }
    if (type == "spheres") return BuildSphereBlas(ParseSphereList(f), options);
    TriangleMesh mesh;
    if (type == "box") {
        // Checked as given: a negative side had made the box of its magnitude.
        const vec3 given = f.Vec3("size", vec3(1.0f));
        if (!(given.x > 0 && given.y > 0 && given.z > 0))
            f.Fail("size", "box sides must be greater than 0");
        if (!(std::max({given.x, given.y, given.z}) <= kMaxModelExtent))
            f.Fail("size", "box sides must be at most 1e6");
        mesh = MakeBoxMesh(given);
        shape = {ModelShape::kBox, 0.0f, 0.5f * mesh.Bounds().Extent()};
    } else if (type == "plane") {
        const vec3 size = f.Vec3("size", vec3(10.0f, 0.0f, 10.0f));
        if (!(size.x > 0 && size.z > 0))
            f.Fail("size", "plane size x and z must be greater than 0");
        // The plane lies in y = 0: a height given would be ignored.
        if (size.y != 0.0f) f.Fail("size", "a plane's size y must be 0 (it lies in y = 0)");
        if (!(std::max(size.x, size.z) <= kMaxModelExtent))
            f.Fail("size", "plane size x and z must be at most 1e6");
        mesh = MakePlaneMesh(size.x, size.z);
        shape = {ModelShape::kPlane, 0.0f, vec3(0.0f)};
    } else if (type == "teapot") {
        const uint32_t resolution = f.Count("resolution", 1, 64, 6);
        mesh = TessellateTeapot(ModelFile(f, "@models/teapot.inc", baseDir), int(resolution));
    } else if (type == "mesh") {
        // Meshes come through the BLAS cache; fitting moves the built BLAS exactly as
        // FitMesh would have moved the mesh's vertices.
        MeshModel model = LoadMeshModel(ModelFile(f, {}, baseDir), options);
        if (f.Has("fit"))
            FitBlas(model.blas, model.info.sourceBounds, FitSize(f, model.info.sourceBounds));
        return std::move(model.blas);
    } else {
        f.Fail("type", "unknown model type \"" + type +
                           "\" (expected sphere, spheres, box, plane, teapot, mesh or gltf)");
    }
    if (f.Has("fit")) FitMesh(mesh, FitSize(f, mesh.Bounds()));
    return BuildTriangleBlas(mesh, options);
}

}  // namespace rtrt
