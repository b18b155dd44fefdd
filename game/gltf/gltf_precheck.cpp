#include "game/gltf/gltf_precheck.h"

#include <cctype>
#include <cstring>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

// glTF's GLB container (spec section 4.4): a 12-byte header, then a JSON chunk and an optional
// BIN chunk. Checked here so that a truncated or foreign file gets a precise message before
// tinygltf sees it.
void CheckGlbHeader(const std::string& file, const std::string& bytes) {
    auto u32 = [&](size_t at) {
        uint32_t v;
        std::memcpy(&v, bytes.data() + at, 4);
        return v;
    };
    if (bytes.size() < 12) throw InputError(file, "header", "truncated: a GLB header is 12 bytes");
    if (bytes.compare(0, 4, "glTF") != 0)
        throw InputError(file, "header.magic", "not a GLB file (it does not start with \"glTF\")");
    if (u32(4) != 2)
        throw InputError(file, "header.version",
                         "GLB version " + std::to_string(u32(4)) + ", rtrt reads version 2");
    if (u32(8) != bytes.size())
        throw InputError(file, "header.length",
                         "the header says " + std::to_string(u32(8)) + " bytes, the file has " +
                             std::to_string(bytes.size()) +
                             (u32(8) > bytes.size() ? " (truncated)" : ""));
    // The fuzzer's first find: a bare 12-byte header, whose JSON chunk GlbJson then read past.
    if (bytes.size() == 12) throw InputError(file, "chunks", "none: a GLB needs a JSON chunk");
    size_t at = 12;
    for (int chunk = 0; at < bytes.size(); ++chunk) {
        const std::string field = JsonIndexed("chunks", size_t(chunk));
        if (bytes.size() - at < 8) throw InputError(file, field, "truncated chunk header");
        const uint64_t length = u32(at);
        if (length > bytes.size() - at - 8)
            throw InputError(file, field + ".length",
                             std::to_string(length) + " bytes do not fit in the file (truncated)");
        if (chunk == 0 && u32(at + 4) != 0x4E4F534Au)
            throw InputError(file, field + ".type", "the first chunk must be JSON");
        at += 8 + length;
    }
}

// The JSON text of a GLB whose header CheckGlbHeader accepted.
std::string GlbJson(const std::string& bytes) {
    uint32_t length;
    std::memcpy(&length, bytes.data() + 12, 4);
    return bytes.substr(20, length);
}

// The JSON types of the fields rtrt reads, per top-level array (glTF 2.0 schema). tinygltf
// treats a field of the wrong type as absent; rtrt rejects it, naming it.
struct FieldKind {
    const char* array;
    const char* field;
    JsonKind kind;
};
constexpr FieldKind kFieldKinds[] = {
    {"nodes", "children", JsonKind::kInts},
    {"nodes", "mesh", JsonKind::kInt},
    {"nodes", "camera", JsonKind::kInt},
    {"nodes", "skin", JsonKind::kInt},
    {"nodes", "translation", JsonKind::kNumbers3},
    {"nodes", "scale", JsonKind::kNumbers3},
    {"nodes", "rotation", JsonKind::kNumbers4},
    {"nodes", "matrix", JsonKind::kNumbers16},
    {"nodes", "extensions", JsonKind::kObject},
    {"scenes", "nodes", JsonKind::kInts},
    {"meshes", "primitives", JsonKind::kObjects},
    {"accessors", "bufferView", JsonKind::kInt},
    {"accessors", "byteOffset", JsonKind::kInt},
    {"accessors", "componentType", JsonKind::kInt},
    {"accessors", "count", JsonKind::kInt},
    {"accessors", "type", JsonKind::kString},
    {"accessors", "normalized", JsonKind::kBool},
    {"bufferViews", "buffer", JsonKind::kInt},
    {"bufferViews", "byteOffset", JsonKind::kInt},
    {"bufferViews", "byteLength", JsonKind::kInt},
    {"bufferViews", "byteStride", JsonKind::kInt},
    {"buffers", "uri", JsonKind::kString},
    {"buffers", "byteLength", JsonKind::kInt},
    {"images", "uri", JsonKind::kString},
    {"textures", "source", JsonKind::kInt},
    {"textures", "sampler", JsonKind::kInt},
    {"materials", "pbrMetallicRoughness", JsonKind::kObject},
    {"materials", "extensions", JsonKind::kObject},
    {"animations", "channels", JsonKind::kObjects},
    {"animations", "samplers", JsonKind::kObjects},
    {"cameras", "type", JsonKind::kString},
};

// Which images a texture's own source names (the ones rtrt can sample).
std::vector<bool> UsedImages(const Json& root) {
    const size_t count =
        root.contains("images") && root["images"].is_array() ? root["images"].size() : 0;
    std::vector<bool> used(count, false);
    if (!root.contains("textures") || !root["textures"].is_array()) return used;
    for (const Json& t : root["textures"])
        if (t.is_object() && t.contains("source") && t["source"].is_number_integer()) {
            const int64_t source = t["source"].get<int64_t>();
            if (source >= 0 && size_t(source) < count) used[size_t(source)] = true;
        }
    return used;
}

// Checked before tinygltf loads the file: the types of the fields rtrt reads (kFieldKinds), and
// that external buffers and images exist, so that the message names the field
// ("buffers[0].uri") where tinygltf's would not.
std::vector<bool> CheckJson(const std::string& file, const std::string& json,
                            const std::string& dir) {
    const Json root = ParseJson(json, file, DuplicateKeys::kLastWins);
    if (!root.is_object()) throw InputError(file, "", "expected a JSON object (a glTF document)");
    for (const char* array : {"nodes", "scenes", "meshes", "accessors", "bufferViews", "buffers",
                              "images", "textures", "materials", "animations", "cameras"}) {
        if (!root.contains(array)) continue;
        const Json& list = root[array];
        if (!IsKind(list, JsonKind::kObjects))
            throw InputError(file, array, "expected an array of objects");
        for (size_t i = 0; i < list.size(); ++i) {
            JsonFields element(list[i], JsonIndexed(array, i), file);
            for (const FieldKind& f : kFieldKinds)
                if (std::strcmp(f.array, array) == 0) element.ExpectKind(f.field, f.kind);
        }
    }
    const std::vector<bool> used = UsedImages(root);
    for (const char* array : {"buffers", "images"}) {
        if (!root.contains(array) || !root[array].is_array()) continue;
        const Json& list = root[array];
        for (size_t i = 0; i < list.size(); ++i) {
            if (!list[i].is_object() || !list[i].contains("uri") || !list[i]["uri"].is_string())
                continue;
            // An image rtrt will not decode may be missing (or a format it cannot read).
            if (std::strcmp(array, "images") == 0 && !used[i]) continue;
            const std::string uri = list[i]["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0) continue;
            std::error_code ec;
            const fs::path path = fs::path(dir.empty() ? "." : dir) / DecodeGltfUri(uri);
            if (!fs::is_regular_file(path, ec))
                throw InputError(file, JsonIndexed(array, i) + ".uri",
                                 "no such file \"" + path.string() + "\"");
        }
    }
    return used;
}

std::string ReadWholeFile(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(path, "", "no such file");
    if (fs::is_directory(path, ec)) throw InputError(path, "", "is a directory, not a glTF file");
    return ReadInputFile(path);
}

}  // namespace

std::string DecodeGltfUri(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) &&
            std::isxdigit(uint8_t(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

GltfFileBytes ReadCheckedGltf(const std::string& file) {
    GltfFileBytes out;
    out.bytes = ReadWholeFile(file);
    std::string lower = fs::path(file).extension().string();
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    out.binary = lower == ".glb" || out.bytes.compare(0, 4, "glTF") == 0;
    if (out.binary) CheckGlbHeader(file, out.bytes);
    out.imageUsed = CheckJson(file, out.binary ? GlbJson(out.bytes) : out.bytes,
                              fs::path(file).parent_path().string());
    return out;
}

}  // namespace rtrt
