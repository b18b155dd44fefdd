#include "game/gltf/gltf_required_fields.h"

#include <algorithm>
#include <initializer_list>
#include <vector>

#include "engine/core/error.h"

namespace rtrt {
namespace {

// The objects of ARRAY in PARENT (none where it is absent or not an array), each with its path.
std::vector<std::pair<const Json*, std::string>> Elements(const Json& parent,
                                                          const std::string& path,
                                                          const char* array) {
    std::vector<std::pair<const Json*, std::string>> out;
    if (!parent.is_object() || !parent.contains(array) || !parent[array].is_array()) return out;
    const Json& list = parent[array];
    const std::string at = path.empty() ? array : path + "." + array;
    for (size_t i = 0; i < list.size(); ++i)
        if (list[i].is_object()) out.emplace_back(&list[i], JsonIndexed(at, i));
    return out;
}

void Require(const std::string& file, const Json& object, const std::string& path,
             std::initializer_list<const char*> keys) {
    for (const char* key : keys)
        if (!object.contains(key))
            throw InputError(file, path + "." + key, "missing (glTF 2.0 requires it)");
}

// KEY of OBJECT, where it is a string, must be one of ALLOWED.
void RequireOneOf(const std::string& file, const Json& object, const std::string& path,
                  const char* key, std::initializer_list<const char*> allowed) {
    if (!object.contains(key) || !object[key].is_string()) return;
    const std::string& value = object[key].get_ref<const std::string&>();
    if (std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return value == a; }))
        return;
    std::string list;
    for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
    throw InputError(file, path + "." + key, "expected one of " + list + ", got \"" + value + "\"");
}

// An object field KEY of OBJECT, where present, as an element with its path.
const Json* Member(const Json& object, const char* key) {
    return object.contains(key) && object[key].is_object() ? &object[key] : nullptr;
}

}  // namespace

void CheckRequiredGltfFields(const std::string& file, const Json& root) {
    if (!root.contains("asset")) throw InputError(file, "asset", "missing (glTF 2.0 requires it)");
    if (!root["asset"].is_object()) throw InputError(file, "asset", "expected an object");
    const Json& asset = root["asset"];
    Require(file, asset, "asset", {"version"});
    if (!asset["version"].is_string())
        throw InputError(file, "asset.version", "expected a string (\"2.0\")");

    for (const auto& [accessor, path] : Elements(root, "", "accessors")) {
        Require(file, *accessor, path, {"componentType", "count", "type"});
        RequireOneOf(file, *accessor, path, "type",
                     {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"});
        if (const Json* sparse = Member(*accessor, "sparse")) {
            const std::string at = path + ".sparse";
            Require(file, *sparse, at, {"count", "indices", "values"});
            if (const Json* indices = Member(*sparse, "indices"))
                Require(file, *indices, at + ".indices", {"bufferView", "componentType"});
            if (const Json* values = Member(*sparse, "values"))
                Require(file, *values, at + ".values", {"bufferView"});
        }
    }
    for (const auto& [animation, path] : Elements(root, "", "animations")) {
        Require(file, *animation, path, {"channels", "samplers"});
        for (const auto& [channel, at] : Elements(*animation, path, "channels")) {
            Require(file, *channel, at, {"sampler", "target"});
            if (const Json* target = Member(*channel, "target"))
                Require(file, *target, at + ".target", {"path"});
        }
        for (const auto& [sampler, at] : Elements(*animation, path, "samplers")) {
            Require(file, *sampler, at, {"input", "output"});
            RequireOneOf(file, *sampler, at, "interpolation", {"LINEAR", "STEP", "CUBICSPLINE"});
        }
    }
    for (const auto& [buffer, path] : Elements(root, "", "buffers"))
        Require(file, *buffer, path, {"byteLength"});
    for (const auto& [view, path] : Elements(root, "", "bufferViews"))
        Require(file, *view, path, {"buffer", "byteLength"});
    for (const auto& [camera, path] : Elements(root, "", "cameras")) {
        Require(file, *camera, path, {"type"});
        RequireOneOf(file, *camera, path, "type", {"perspective", "orthographic"});
        const std::string type =
            camera->at("type").is_string() ? camera->at("type").get<std::string>() : "";
        if (type.empty()) continue;
        Require(file, *camera, path, {type.c_str()});
        if (const Json* projection = Member(*camera, type.c_str())) {
            if (type == "perspective")
                Require(file, *projection, path + ".perspective", {"yfov", "znear"});
            else
                Require(file, *projection, path + ".orthographic",
                        {"xmag", "ymag", "zfar", "znear"});
        }
    }
    for (const auto& [image, path] : Elements(root, "", "images"))
        if (!image->contains("uri") && !image->contains("bufferView"))
            throw InputError(file, path, "give a uri or a bufferView (glTF 2.0 requires one)");
    for (const auto& [mesh, path] : Elements(root, "", "meshes")) {
        Require(file, *mesh, path, {"primitives"});
        for (const auto& [primitive, at] : Elements(*mesh, path, "primitives"))
            Require(file, *primitive, at, {"attributes"});
    }
    for (const auto& [material, path] : Elements(root, "", "materials"))
        RequireOneOf(file, *material, path, "alphaMode", {"OPAQUE", "MASK", "BLEND"});
    for (const auto& [skin, path] : Elements(root, "", "skins"))
        Require(file, *skin, path, {"joints"});
}

}  // namespace rtrt
