#include "game/gltf/gltf_draco.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "game/gltf/gltf_glb.h"
#include "game/gltf/gltf_precheck.h"
#include "game/scene/json_fields.h"

#if RTRT_WITH_DRACO
#include <draco/compression/decode.h>
#endif

namespace rtrt {
namespace {

namespace fs = std::filesystem;

constexpr const char* kDraco = "KHR_draco_mesh_compression";
// RFC 4648 base64 (a data URI's payload); nullopt for a character outside the alphabet.
std::optional<std::string> DecodeBase64(const std::string& text) {
    std::string out;
    uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
        int v;
        if (c >= 'A' && c <= 'Z')
            v = c - 'A';
        else if (c >= 'a' && c <= 'z')
            v = c - 'a' + 26;
        else if (c >= '0' && c <= '9')
            v = c - '0' + 52;
        else if (c == '+')
            v = 62;
        else if (c == '/')
            v = 63;
        else if (c == '=')
            break;
        else
            return std::nullopt;
        bits = bits << 6 | uint32_t(v);
        if ((count += 6) >= 8) {
            count -= 8;
            out += char((bits >> count) & 0xFF);
        }
    }
    return out;
}

// The bytes of buffers[INDEX]: a GLB's BIN chunk, a base64 data URI or a file beside the glTF.
std::string BufferBytes(const std::string& file, const Json& root, size_t index,
                        const GlbChunks* glb, const std::string& dir) {
    const std::string field = JsonIndexed("buffers", index);
    const Json& buffer = root["buffers"][index];
    if (!buffer.contains("uri")) {
        if (glb && glb->hasBin && index == 0) return glb->bin;
        throw InputError(file, field, "has no uri and is not a GLB's BIN chunk");
    }
    const std::string uri = buffer["uri"].get<std::string>();
    if (uri.rfind("data:", 0) == 0) {
        const size_t comma = uri.find(";base64,");
        std::optional<std::string> data;
        if (comma != std::string::npos) data = DecodeBase64(uri.substr(comma + 8));
        if (!data) throw InputError(file, field + ".uri", "not a base64 data URI");
        return *data;
    }
    const fs::path path = fs::path(dir.empty() ? "." : dir) / DecodeGltfUri(uri);
    try {
        return ReadAssetFile(path.string());
    } catch (const InputError& e) {
        throw InputError(file, field + ".uri", "\"" + path.string() + "\": " + e.Reason());
    }
}

bool UsesDraco(const Json& primitive) {
    return primitive.is_object() && primitive.contains("extensions") &&
           primitive["extensions"].is_object() && primitive["extensions"].contains(kDraco);
}

// Whether the primitive's accessors (attributes and indices) all carry uncompressed data, so
// that the Draco stream need not be decoded.
bool HasUncompressedFallback(const Json& root, const Json& primitive) {
    const Json& accessors = root["accessors"];
    auto hasView = [&](const Json& index) {
        return index.is_number_integer() && index.get<int64_t>() >= 0 &&
               size_t(index.get<int64_t>()) < accessors.size() &&
               accessors[size_t(index.get<int64_t>())].contains("bufferView");
    };
    if (primitive.contains("indices") && !hasView(primitive["indices"])) return false;
    if (!primitive.contains("attributes") || !primitive["attributes"].is_object()) return false;
    for (const auto& [name, index] : primitive["attributes"].items())
        if (!hasView(index)) return false;
    return true;
}

// Removes the extension's name from extensionsRequired and extensionsUsed.
void ForgetExtension(Json& root) {
    for (const char* list : {"extensionsRequired", "extensionsUsed"}) {
        if (!root.contains(list) || !root[list].is_array()) continue;
        Json kept = Json::array();
        for (const Json& name : root[list])
            if (name != kDraco) kept.push_back(name);
        if (kept.empty())
            root.erase(list);
        else
            root[list] = kept;
    }
}

#if RTRT_WITH_DRACO

size_t ComponentCount(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    return 0;
}

size_t ComponentBytes(int componentType) {
    switch (componentType) {
        case 5120:
        case 5121:
            return 1;
        case 5122:
        case 5123:
            return 2;
        case 5125:
        case 5126:
            return 4;
        default:
            return 0;
    }
}

// Appends one accessor's decoded data to OUT (4-byte aligned), returning its offset there.
size_t AppendAligned(std::string& out, const std::vector<uint8_t>& data) {
    while (out.size() % 4) out += '\0';
    const size_t offset = out.size();
    out.append(reinterpret_cast<const char*>(data.data()), data.size());
    return offset;
}

template <typename T>
bool ConvertAll(const draco::PointAttribute& attribute, uint32_t points, size_t components,
                std::vector<uint8_t>& out) {
    out.resize(size_t(points) * components * sizeof(T));
    T* values = reinterpret_cast<T*>(out.data());
    for (uint32_t p = 0; p < points; ++p)
        if (!attribute.ConvertValue<T>(attribute.mapped_index(draco::PointIndex(p)),
                                       int8_t(components), values + size_t(p) * components))
            return false;
    return true;
}

// The attribute's values for every point, in the accessor's component type.
bool ConvertAttribute(const draco::PointAttribute& attribute, uint32_t points, size_t components,
                      int componentType, std::vector<uint8_t>& out) {
    switch (componentType) {
        case 5120:
            return ConvertAll<int8_t>(attribute, points, components, out);
        case 5121:
            return ConvertAll<uint8_t>(attribute, points, components, out);
        case 5122:
            return ConvertAll<int16_t>(attribute, points, components, out);
        case 5123:
            return ConvertAll<uint16_t>(attribute, points, components, out);
        case 5125:
            return ConvertAll<uint32_t>(attribute, points, components, out);
        case 5126:
            return ConvertAll<float>(attribute, points, components, out);
        default:
            return false;
    }
}

// Decodes one primitive's stream and points its accessors at the decoded data in BIN.
class PrimitiveDecoder {
  public:
    PrimitiveDecoder(const std::string& file, Json& root, const std::string& field)
        : file_(file), root_(root), field_(field) {}

    void Decode(Json& primitive, const std::string& stream, std::string& bin, int binBuffer) {
        draco::DecoderBuffer buffer;
        buffer.Init(stream.data(), stream.size());
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
        if (!decoded.ok())
            Fail("", "libdraco cannot decode the stream: " + decoded.status().error_msg_string());
        const draco::Mesh& mesh = *decoded.value();
        const Json& ext = primitive["extensions"][kDraco];
        const Json& attributes = primitive["attributes"];
        for (const auto& [name, id] : ext["attributes"].items()) {
            if (!attributes.contains(name))
                Fail(".attributes." + name, "the primitive has no " + name + " accessor to fill");
            const draco::PointAttribute* attribute =
                id.is_number_integer() && id.get<int64_t>() >= 0
                    ? mesh.GetAttributeByUniqueId(uint32_t(id.get<int64_t>()))
                    : nullptr;
            if (!attribute) Fail(".attributes." + name, "the stream has no attribute with this id");
            const size_t accessor = AccessorIndex(attributes[name], ".attributes." + name);
            if (root_["accessors"][accessor].contains("bufferView")) continue;
            Json& a = root_["accessors"][accessor];
            const size_t components = ComponentCount(a.value("type", std::string()));
            if (components == 0 || components < attribute->num_components())
                Fail(".attributes." + name,
                     "accessor " + std::to_string(accessor) + "'s type " +
                         a.value("type", std::string("(none)")) + " cannot hold the stream's " +
                         std::to_string(attribute->num_components()) + " components");
            if (a.value("count", int64_t(-1)) != int64_t(mesh.num_points()))
                Fail(".attributes." + name, "accessor " + std::to_string(accessor) + " has count " +
                                                std::to_string(a.value("count", int64_t(-1))) +
                                                ", the stream " +
                                                std::to_string(mesh.num_points()) + " points");
            std::vector<uint8_t> data;
            if (!ConvertAttribute(*attribute, mesh.num_points(), components,
                                  a.value("componentType", 0), data))
                Fail(".attributes." + name, "the stream's values do not convert to accessor " +
                                                std::to_string(accessor) + "'s component type");
            Point(a, AddView(bin, binBuffer, data));
        }
        FillIndices(primitive, mesh, bin, binBuffer);
        primitive["mode"] = 4;
    }

  private:
    [[noreturn]] void Fail(const std::string& suffix, const std::string& reason) const {
        throw InputError(file_, field_ + suffix, reason);
    }

    size_t AccessorIndex(const Json& index, const std::string& suffix) const {
        if (!index.is_number_integer() || index.get<int64_t>() < 0 ||
            size_t(index.get<int64_t>()) >= root_["accessors"].size())
            Fail(suffix, "names no accessor");
        return size_t(index.get<int64_t>());
    }

    size_t AddView(std::string& bin, int binBuffer, const std::vector<uint8_t>& data) {
        const size_t offset = AppendAligned(bin, data);
        root_["bufferViews"].push_back(
            {{"buffer", binBuffer}, {"byteOffset", offset}, {"byteLength", data.size()}});
        return root_["bufferViews"].size() - 1;
    }

    static void Point(Json& accessor, size_t view) {
        accessor["bufferView"] = view;
        accessor.erase("byteOffset");
        accessor.erase("sparse");
    }

    void FillIndices(Json& primitive, const draco::Mesh& mesh, std::string& bin, int binBuffer) {
        const uint64_t count = uint64_t(mesh.num_faces()) * 3;
        int componentType = 5125;
        Json* accessor = nullptr;
        if (primitive.contains("indices")) {
            const size_t index = AccessorIndex(primitive["indices"], ".indices");
            accessor = &root_["accessors"][index];
            if (accessor->contains("bufferView")) return;
            componentType = accessor->value("componentType", 0);
            if (accessor->value("count", int64_t(-1)) != int64_t(count))
                Fail(".indices", "accessor " + std::to_string(index) + " has count " +
                                     std::to_string(accessor->value("count", int64_t(-1))) +
                                     ", the stream " + std::to_string(count) + " indices");
        }
        const size_t bytes = ComponentBytes(componentType);
        if (bytes == 0 || componentType == 5120 || componentType == 5122 || componentType == 5126)
            Fail(".indices", "indices must be unsigned bytes, shorts or ints");
        const uint64_t limit = bytes == 4 ? 0xFFFFFFFFull : (1ull << (8 * bytes)) - 1;
        std::vector<uint8_t> data(size_t(count) * bytes);
        for (uint32_t f = 0; f < mesh.num_faces(); ++f)
            for (int corner = 0; corner < 3; ++corner) {
                const uint64_t v = mesh.face(draco::FaceIndex(f))[corner].value();
                if (v > limit)
                    Fail(".indices", "index " + std::to_string(v) + " does not fit the accessor");
                const uint32_t v32 = uint32_t(v);
                std::memcpy(data.data() + (size_t(f) * 3 + corner) * bytes, &v32, bytes);
            }
        if (!accessor) {
            root_["accessors"].push_back(
                {{"componentType", 5125}, {"count", count}, {"type", "SCALAR"}});
            primitive["indices"] = root_["accessors"].size() - 1;
            accessor = &root_["accessors"].back();
        }
        Point(*accessor, AddView(bin, binBuffer, data));
    }

    const std::string& file_;
    Json& root_;
    std::string field_;
};

#endif

// The Draco stream of one primitive: the extension's bufferView within its buffer.
std::string StreamBytes(const std::string& file, const Json& root, const Json& ext,
                        const std::string& field, const GlbChunks* glb, const std::string& dir,
                        std::vector<std::optional<std::string>>& buffers) {
    if (!ext.is_object() || !ext.contains("bufferView") || !ext["bufferView"].is_number_integer() ||
        !ext.contains("attributes") || !ext["attributes"].is_object())
        throw InputError(file, field,
                         "expected an object with an integer bufferView and an attributes object");
    const int64_t viewIndex = ext["bufferView"].get<int64_t>();
    if (!root.contains("bufferViews") || viewIndex < 0 ||
        size_t(viewIndex) >= root["bufferViews"].size())
        throw InputError(file, field + ".bufferView", "names no buffer view");
    const Json& view = root["bufferViews"][size_t(viewIndex)];
    const std::string viewField = JsonIndexed("bufferViews", size_t(viewIndex));
    const int64_t buffer = view.value("buffer", int64_t(-1));
    if (!root.contains("buffers") || buffer < 0 || size_t(buffer) >= root["buffers"].size())
        throw InputError(file, viewField + ".buffer", "names no buffer");
    std::optional<std::string>& bytes = buffers[size_t(buffer)];
    if (!bytes) bytes = BufferBytes(file, root, size_t(buffer), glb, dir);
    const int64_t offset = view.value("byteOffset", int64_t(0));
    const int64_t length = view.value("byteLength", int64_t(-1));
    if (offset < 0 || length < 0 || uint64_t(offset) + uint64_t(length) > bytes->size())
        throw InputError(file, viewField,
                         "bytes " + std::to_string(offset) + "+" + std::to_string(length) +
                             " lie outside buffer " + std::to_string(buffer) + " (" +
                             std::to_string(bytes->size()) + " bytes)");
    return bytes->substr(size_t(offset), size_t(length));
}

}  // namespace

bool DracoAvailable() { return RTRT_WITH_DRACO != 0; }

std::optional<DracoDecoded> DecodeDracoPrimitives(const std::string& file, const std::string& bytes,
                                                  bool binary, const std::string& dir) {
    const std::string_view json =
        binary ? std::string_view(bytes).substr(20, GlbWord(bytes, 12)) : std::string_view(bytes);
    if (json.find(kDraco) == std::string_view::npos) return std::nullopt;
    DracoDecoded out;
    std::optional<GlbChunks> glb;
    if (binary) glb = SplitGlb(bytes);
    Json root = ParseJson(binary ? glb->json : bytes, file, DuplicateKeys::kLastWins);
    if (!root.is_object() || !root.contains("meshes") || !root["meshes"].is_array())
        return std::nullopt;
    // The decoded data goes into buffer 0, the BIN chunk of the GLB written at the end: after a
    // GLB's own BIN data, or as a new first buffer (every view's buffer shifting by one).
    const bool keepsBin = glb && glb->hasBin && root.contains("buffers") &&
                          root["buffers"].is_array() && !root["buffers"].empty() &&
                          !root["buffers"][0].contains("uri");
    std::string bin = keepsBin ? glb->bin : std::string();
    const size_t bufferCount =
        root.contains("buffers") && root["buffers"].is_array() ? root["buffers"].size() : 0;
    std::vector<std::optional<std::string>> buffers(bufferCount);
    if (!root.contains("bufferViews")) root["bufferViews"] = Json::array();
    if (!root.contains("accessors")) root["accessors"] = Json::array();
    const size_t fileViews = root["bufferViews"].size();
    Json& meshes = root["meshes"];
    for (size_t m = 0; m < meshes.size(); ++m) {
        if (!meshes[m].is_object() || !meshes[m].contains("primitives")) continue;
        Json& primitives = meshes[m]["primitives"];
        for (size_t p = 0; p < primitives.size(); ++p) {
            Json& primitive = primitives[p];
            if (!UsesDraco(primitive)) continue;
            const std::string field =
                JsonIndexed(JsonIndexed("meshes", m) + ".primitives", p) + ".extensions." + kDraco;
            if (HasUncompressedFallback(root, primitive)) continue;
            const std::string stream = StreamBytes(file, root, primitive["extensions"][kDraco],
                                                   field, glb ? &*glb : nullptr, dir, buffers);
            if (!DracoAvailable())
                throw InputError(file, field,
                                 "this rtrt was built without libdraco (install libdraco-dev and "
                                 "rebuild), or decompress the file (gltf-transform copy IN OUT)");
#if RTRT_WITH_DRACO
            PrimitiveDecoder(file, root, field).Decode(primitive, stream, bin, 0);
#endif
            primitive["extensions"].erase(kDraco);
            if (primitive["extensions"].empty()) primitive.erase("extensions");
            ++out.primitives;
        }
    }
    if (out.primitives == 0) return std::nullopt;
    ForgetExtension(root);
    if (!keepsBin) {
        // The decoded views already name buffer 0; the file's own views shift to make room.
        for (size_t v = 0; v < fileViews; ++v)
            if (root["bufferViews"][v].contains("buffer") &&
                root["bufferViews"][v]["buffer"].is_number_integer())
                root["bufferViews"][v]["buffer"] =
                    root["bufferViews"][v]["buffer"].get<int64_t>() + 1;
        if (!root.contains("buffers")) root["buffers"] = Json::array();
        root["buffers"].insert(root["buffers"].begin(), Json::object());
    }
    root["buffers"][0]["byteLength"] = bin.size();
    out.glb = MakeGlb(root.dump(), std::move(bin));
    return out;
}

}  // namespace rtrt
