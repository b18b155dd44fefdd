#include "game/gltf/gltf_references.h"

#include <algorithm>
#include <climits>
#include <initializer_list>

#include "engine/core/error.h"

namespace rtrt {
namespace {

// An index field (glTF's glTFid) of each object of ARRAY, a dotted path inside it, that names an
// object of TARGET (one index, or an array of them).
struct Reference {
    const char* array;
    const char* field;
    const char* target;
    const char* noun;  // one object of TARGET, as messages name it
    bool list = false;
};
constexpr Reference kReferences[] = {
    {"scenes", "nodes", "nodes", "node", true},
    {"nodes", "children", "nodes", "node", true},
    {"nodes", "mesh", "meshes", "mesh"},
    {"nodes", "camera", "cameras", "camera"},
    {"nodes", "skin", "skins", "skin"},
    {"skins", "joints", "nodes", "node", true},
    {"skins", "skeleton", "nodes", "node"},
    {"skins", "inverseBindMatrices", "accessors", "accessor"},
    {"accessors", "bufferView", "bufferViews", "buffer view"},
    {"accessors", "sparse.indices.bufferView", "bufferViews", "buffer view"},
    {"accessors", "sparse.values.bufferView", "bufferViews", "buffer view"},
    {"bufferViews", "buffer", "buffers", "buffer"},
    {"images", "bufferView", "bufferViews", "buffer view"},
    {"textures", "source", "images", "image"},
    {"textures", "sampler", "samplers", "sampler"},
};

// The value at FIELD's dotted path inside ELEMENT, or null where a part is absent or its parent
// is no object.
const Json* At(const Json& element, const std::string& field) {
    const Json* at = &element;
    size_t start = 0;
    while (true) {
        const size_t dot = field.find('.', start);
        const std::string key = field.substr(start, dot - start);
        if (!at->is_object() || !at->contains(key)) return nullptr;
        at = &(*at)[key];
        if (dot == std::string::npos) return at;
        start = dot + 1;
    }
}

size_t Count(const Json& root, const char* array) {
    return root.contains(array) && root[array].is_array() ? root[array].size() : 0;
}

// VALUE, at the field AT, must name one of COUNT objects of TARGET.
void CheckIndex(const std::string& file, const Json& value, const std::string& at,
                const std::string& target, const std::string& noun, size_t count) {
    if (!value.is_number_integer())
        throw InputError(file, at,
                         std::string("expected an index (an integer), got ") + value.type_name());
    const bool inRange = value.is_number_unsigned()
                             ? value.get<uint64_t>() < count
                             : value.get<int64_t>() >= 0 && uint64_t(value.get<int64_t>()) < count;
    if (!inRange)
        throw InputError(file, at,
                         noun + " " + value.dump() + " out of range (the file has " +
                             std::to_string(count) + " in " + target + ")");
}

// An index, or with LIST an array of indices, at the field AT.
void CheckReference(const std::string& file, const Json& value, const std::string& at,
                    const std::string& target, const std::string& noun, size_t count, bool list) {
    if (!list) return CheckIndex(file, value, at, target, noun, count);
    if (!value.is_array()) throw InputError(file, at, "expected an array of indices");
    for (size_t i = 0; i < value.size(); ++i)
        CheckIndex(file, value[i], JsonIndexed(at, i), target, noun, count);
}

// Each primitive's material and accessors, and each animation's channels and samplers: indices
// inside arrays of objects.
void CheckNestedReferences(const std::string& file, const Json& root) {
    const size_t accessors = Count(root, "accessors");
    for (size_t m = 0; m < Count(root, "meshes"); ++m) {
        const Json* primitives = At(root["meshes"][m], "primitives");
        if (!primitives || !primitives->is_array()) continue;
        for (size_t p = 0; p < primitives->size(); ++p) {
            const Json& primitive = (*primitives)[p];
            const std::string at = JsonIndexed(JsonIndexed("meshes", m) + ".primitives", p);
            if (const Json* material = At(primitive, "material"))
                CheckIndex(file, *material, at + ".material", "materials", "material",
                           Count(root, "materials"));
            if (const Json* indices = At(primitive, "indices"))
                CheckIndex(file, *indices, at + ".indices", "accessors", "accessor", accessors);
            if (const Json* attributes = At(primitive, "attributes");
                attributes && attributes->is_object())
                for (const auto& [name, value] : attributes->items())
                    CheckIndex(file, value, at + ".attributes." + name, "accessors", "accessor",
                               accessors);
            const Json* targets = At(primitive, "targets");
            if (!targets || !targets->is_array()) continue;
            for (size_t t = 0; t < targets->size(); ++t) {
                if (!(*targets)[t].is_object()) continue;
                for (const auto& [name, value] : (*targets)[t].items())
                    CheckIndex(file, value, JsonIndexed(at + ".targets", t) + "." + name,
                               "accessors", "accessor", accessors);
            }
        }
    }
    for (size_t a = 0; a < Count(root, "animations"); ++a) {
        const Json& animation = root["animations"][a];
        const std::string at = JsonIndexed("animations", a);
        const Json* samplers = At(animation, "samplers");
        const size_t samplerCount = samplers && samplers->is_array() ? samplers->size() : 0;
        for (size_t s = 0; s < samplerCount; ++s)
            for (const char* key : {"input", "output"})
                if (const Json* value = At((*samplers)[s], key))
                    CheckIndex(file, *value, JsonIndexed(at + ".samplers", s) + "." + key,
                               "accessors", "accessor", accessors);
        const Json* channels = At(animation, "channels");
        if (!channels || !channels->is_array()) continue;
        for (size_t c = 0; c < channels->size(); ++c) {
            const std::string channelAt = JsonIndexed(at + ".channels", c);
            if (const Json* sampler = At((*channels)[c], "sampler"))
                CheckIndex(file, *sampler, channelAt + ".sampler", at + ".samplers", "sampler",
                           samplerCount);
            if (const Json* node = At((*channels)[c], "target.node"))
                CheckIndex(file, *node, channelAt + ".target.node", "nodes", "node",
                           Count(root, "nodes"));
        }
    }
    if (root.contains("scene"))
        CheckIndex(file, root["scene"], "scene", "scenes", "scene", Count(root, "scenes"));
}

// A buffer view's bytes lie inside its buffer (glTF 2.0, 3.6.2): images are decoded from them
// before any accessor check sees the view.
void CheckBufferViews(const std::string& file, const Json& root) {
    for (size_t v = 0; v < Count(root, "bufferViews"); ++v) {
        const Json& view = root["bufferViews"][v];
        const Json* buffer = At(view, "buffer");
        const Json* length = At(view, "byteLength");
        if (!buffer || !length || !length->is_number_integer()) continue;
        const Json& target = root["buffers"][buffer->get<size_t>()];
        if (!target.contains("byteLength") || !target["byteLength"].is_number_integer()) continue;
        const Json* offset = At(view, "byteOffset");
        const uint64_t from = offset && offset->is_number_integer() ? offset->get<uint64_t>() : 0;
        const uint64_t bytes = length->get<uint64_t>();
        const uint64_t size = target["byteLength"].get<uint64_t>();
        if (from > size || bytes > size - from)
            throw InputError(file, JsonIndexed("bufferViews", v) + ".byteLength",
                             "bytes " + std::to_string(from) + " + " + std::to_string(bytes) +
                                 " lie outside buffer " + buffer->dump() + " of " +
                                 std::to_string(size) + " bytes");
    }
}

// KEY of a sampler, where given, must be one of ALLOWED (glTF's GL enumerations).
void CheckSamplerEnum(const std::string& file, const Json& sampler, const std::string& at,
                      const char* key, std::initializer_list<int> allowed) {
    if (!sampler.contains(key)) return;
    const Json& value = sampler[key];
    const bool known = value.is_number_integer() && std::any_of(allowed.begin(), allowed.end(),
                                                                [&](int a) { return value == a; });
    if (known) return;
    std::string list;
    for (int a : allowed) list += (list.empty() ? "" : ", ") + std::to_string(a);
    throw InputError(file, at + "." + key, "expected one of " + list + ", got " + value.dump());
}

}  // namespace

void CheckGltfReferences(const std::string& file, const Json& root) {
    for (const Reference& r : kReferences)
        for (size_t i = 0; i < Count(root, r.array); ++i)
            if (const Json* value = At(root[r.array][i], r.field))
                CheckReference(file, *value, JsonIndexed(r.array, i) + "." + r.field, r.target,
                               r.noun, Count(root, r.target), r.list);
    for (size_t m = 0; m < Count(root, "materials"); ++m)
        for (const char* slot : kGltfTextureSlots)
            if (const Json* value = At(root["materials"][m], std::string(slot) + ".index"))
                CheckIndex(file, *value, JsonIndexed("materials", m) + "." + slot + ".index",
                           "textures", "texture", Count(root, "textures"));
    CheckNestedReferences(file, root);
    CheckBufferViews(file, root);
    for (size_t m = 0; m < Count(root, "materials"); ++m)
        for (const char* slot : kGltfTextureSlots)
            for (const std::string field :
                 {std::string(slot) + ".texCoord",
                  std::string(slot) + ".extensions.KHR_texture_transform.texCoord"}) {
                const Json* value = At(root["materials"][m], field);
                if (value && value->is_number_integer() &&
                    !(value->is_number_unsigned() ? value->get<uint64_t>() <= INT_MAX
                                                  : value->get<int64_t>() >= 0))
                    throw InputError(file, JsonIndexed("materials", m) + "." + field,
                                     "must be a set index from 0, got " + value->dump());
            }
    for (size_t s = 0; s < Count(root, "samplers"); ++s) {
        const Json& sampler = root["samplers"][s];
        const std::string at = JsonIndexed("samplers", s);
        CheckSamplerEnum(file, sampler, at, "magFilter", {9728, 9729});
        CheckSamplerEnum(file, sampler, at, "minFilter", {9728, 9729, 9984, 9985, 9986, 9987});
        CheckSamplerEnum(file, sampler, at, "wrapS", {33071, 33648, 10497});
        CheckSamplerEnum(file, sampler, at, "wrapT", {33071, 33648, 10497});
    }
}

}  // namespace rtrt
