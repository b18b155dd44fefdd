#include "game/gltf/gltf_precheck.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "game/gltf/gltf_references.h"
#include "game/gltf/gltf_required_fields.h"
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

// The JSON types of the fields rtrt reads, per top-level array (glTF 2.0 schema), a dotted field
// inside the objects before it (each listed after its parent). tinygltf treats a field of the
// wrong type as absent (a metallicFactor of "0" rendered as metal); rtrt rejects it, naming it.
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
    {"materials", "pbrMetallicRoughness.baseColorFactor", JsonKind::kNumbers4},
    {"materials", "pbrMetallicRoughness.metallicFactor", JsonKind::kNumber},
    {"materials", "pbrMetallicRoughness.roughnessFactor", JsonKind::kNumber},
    {"materials", "normalTexture.scale", JsonKind::kNumber},
    {"materials", "occlusionTexture.strength", JsonKind::kNumber},
    {"materials", "emissiveFactor", JsonKind::kNumbers3},
    {"materials", "alphaMode", JsonKind::kString},
    {"materials", "alphaCutoff", JsonKind::kNumber},
    {"materials", "doubleSided", JsonKind::kBool},
    {"materials", "extensions", JsonKind::kObject},
    {"materials", "extensions.KHR_materials_transmission", JsonKind::kObject},
    {"materials", "extensions.KHR_materials_transmission.transmissionFactor", JsonKind::kNumber},
    {"materials", "extensions.KHR_materials_volume", JsonKind::kObject},
    {"materials", "extensions.KHR_materials_volume.thicknessFactor", JsonKind::kNumber},
    {"materials", "extensions.KHR_materials_ior", JsonKind::kObject},
    {"materials", "extensions.KHR_materials_ior.ior", JsonKind::kNumber},
    {"materials", "extensions.KHR_materials_specular", JsonKind::kObject},
    {"materials", "extensions.KHR_materials_specular.specularFactor", JsonKind::kNumber},
    {"materials", "extensions.KHR_materials_specular.specularColorFactor", JsonKind::kNumbers3},
    {"materials", "extensions.KHR_materials_emissive_strength", JsonKind::kObject},
    {"materials", "extensions.KHR_materials_emissive_strength.emissiveStrength", JsonKind::kNumber},
    {"animations", "channels", JsonKind::kObjects},
    {"animations", "samplers", JsonKind::kObjects},
    {"cameras", "type", JsonKind::kString},
    {"samplers", "magFilter", JsonKind::kInt},
    {"samplers", "minFilter", JsonKind::kInt},
    {"samplers", "wrapS", JsonKind::kInt},
    {"samplers", "wrapT", JsonKind::kInt},
};

// The fields of a textureInfo (each of kGltfTextureSlots), the slot itself first.
struct SlotFieldKind {
    const char* field;  // "" for the slot's own object
    JsonKind kind;
};
constexpr SlotFieldKind kTextureInfoKinds[] = {
    {"", JsonKind::kObject},
    {".index", JsonKind::kInt},
    {".texCoord", JsonKind::kInt},
    {".extensions", JsonKind::kObject},
    {".extensions.KHR_texture_transform", JsonKind::kObject},
    {".extensions.KHR_texture_transform.rotation", JsonKind::kNumber},
    {".extensions.KHR_texture_transform.texCoord", JsonKind::kInt},
};

// Lower bounds of integer fields of kFieldKinds (glTF 2.0's schema; byte lengths of 0, below its
// minimum of 1, are let through as tinygltf reads them).
struct FieldMinimum {
    const char* array;
    const char* field;
    int64_t minimum;
};
constexpr FieldMinimum kFieldMinimums[] = {
    {"accessors", "byteOffset", 0},
    {"bufferViews", "byteOffset", 0},
    {"bufferViews", "byteLength", 0},
    {"buffers", "byteLength", 0},
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

// The data URIs tinygltf decodes; it reads any other as a file's name, and the image then was
// "missing or could not be decoded" though its bytes were there.
void CheckDataUriType(const std::string& file, const std::string& field, const std::string& uri) {
    constexpr std::string_view kRead[] = {"application/octet-stream",
                                          "application/gltf-buffer",
                                          "image/png",
                                          "image/jpeg",
                                          "image/bmp",
                                          "image/gif",
                                          "text/plain"};
    for (std::string_view type : kRead)
        if (uri.compare(5, type.size(), type) == 0 &&
            uri.compare(5 + type.size(), 8, ";base64,") == 0)
            return;
    const std::string type = uri.substr(5, std::min(uri.find_first_of(";,"), size_t(64)) - 5);
    throw InputError(file, field + ".uri",
                     "a data URI of type \"" + type +
                         "\", which rtrt does not read; it reads base64 data of "
                         "application/octet-stream, image/png, image/jpeg, image/bmp or image/gif");
}

// A buffer given as a base64 data URI must hold exactly its byteLength bytes (tinygltf refuses
// it otherwise, with a message that quotes the whole URI and not the reason).
void CheckBufferDataUri(const std::string& file, const std::string& field, const Json& buffer) {
    const std::string& uri = buffer["uri"].get_ref<const std::string&>();
    const size_t comma = uri.find(',');
    if (comma == std::string::npos || comma < 7 || uri.compare(comma - 7, 7, ";base64") != 0)
        throw InputError(file, field + ".uri",
                         "a data URI must hold base64 data (\"data:application/octet-stream;"
                         "base64,...\")");
    const std::string_view payload = std::string_view(uri).substr(comma + 1);
    size_t padding = 0;
    while (padding < payload.size() && padding < 2 && payload[payload.size() - 1 - padding] == '=')
        ++padding;
    for (size_t c = 0; c + padding < payload.size(); ++c) {
        const unsigned char ch = uint8_t(payload[c]);
        if (!(std::isalnum(ch) || ch == '+' || ch == '/'))
            throw InputError(file, field + ".uri",
                             "the data URI's payload is not base64 (character " +
                                 std::to_string(comma + 1 + c) + ")");
    }
    // Four characters carry three bytes; a last group of 2 or 3 characters carries 1 or 2.
    const size_t characters = payload.size() - padding;
    if (characters % 4 == 1)
        throw InputError(file, field + ".uri",
                         "the data URI's base64 payload ends in a lone character (truncated?)");
    const uint64_t bytes = characters / 4 * 3 + (characters % 4 == 0 ? 0 : characters % 4 - 1);
    if (bytes == 0) throw InputError(file, field + ".uri", "the data URI holds no data");
    if (buffer.contains("byteLength") && buffer["byteLength"].is_number_integer() &&
        buffer["byteLength"].get<int64_t>() != int64_t(bytes))
        throw InputError(file, field + ".byteLength",
                         std::to_string(buffer["byteLength"].get<int64_t>()) +
                             ", but the data URI holds " + std::to_string(bytes) + " bytes");
}

// Checked before tinygltf loads the file: the types of the fields rtrt reads (kFieldKinds), and
// that external buffers and images exist, so that the message names the field
// ("buffers[0].uri") where tinygltf's would not.
// tinygltf turns JSON into its values recursively, so that extras nested 20,000 deep (a 40 KB
// file) overflowed the stack: deeper nesting than any glTF needs is refused before it sees it.
constexpr int kMaxJsonDepth = 256;

void CheckJsonDepth(const std::string& file, const std::string& json) {
    int depth = 0;
    for (size_t i = 0; i < json.size(); ++i) {
        const char c = json[i];
        if (c == '"') {  // past the string, escapes included
            for (++i; i < json.size() && json[i] != '"'; ++i)
                if (json[i] == '\\') ++i;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                throw InputError(file, "",
                                 "the JSON is nested more than " + std::to_string(kMaxJsonDepth) +
                                     " levels deep (at byte " + std::to_string(i) +
                                     "); no glTF needs that");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

// FIELD's kind where it is given: its dots name the objects it sits in, whose own kinds are
// checked before it (an absent or other parent leaves nothing to check here).
void ExpectNestedKind(const std::string& file, const Json& element, const std::string& at,
                      const std::string& field, JsonKind kind) {
    const Json* parent = &element;
    std::string path = at;
    size_t start = 0;
    for (size_t dot; (dot = field.find('.', start)) != std::string::npos; start = dot + 1) {
        const std::string key = field.substr(start, dot - start);
        if (!parent->contains(key) || !(*parent)[key].is_object()) return;
        parent = &(*parent)[key];
        path += "." + key;
    }
    JsonFields(*parent, path, file).ExpectKind(field.substr(start), kind);
}

// The first animation's channels that name a target.node (GltfFileBytes).
std::vector<size_t> ChannelsWithNodes(const Json& root) {
    std::vector<size_t> kept;
    if (!root.contains("animations") || root["animations"].empty()) return kept;
    const Json& animation = root["animations"][0];
    if (!animation.contains("channels") || !animation["channels"].is_array()) return kept;
    const Json& channels = animation["channels"];
    for (size_t c = 0; c < channels.size(); ++c) {
        const Json& channel = channels[c];
        const bool named = channel.is_object() && channel.contains("target") &&
                           channel["target"].is_object() && channel["target"].contains("node");
        if (named) kept.push_back(c);
    }
    return kept;
}

std::vector<bool> CheckJson(const std::string& file, const std::string& json,
                            const std::string& dir, std::vector<size_t>* channels) {
    CheckJsonDepth(file, json);
    const Json root = ParseJson(json, file, DuplicateKeys::kLastWins);
    if (!root.is_object()) throw InputError(file, "", "expected a JSON object (a glTF document)");
    for (const char* array :
         {"nodes", "scenes", "meshes", "accessors", "bufferViews", "buffers", "images", "textures",
          "materials", "animations", "cameras", "skins", "samplers"}) {
        if (!root.contains(array)) continue;
        const Json& list = root[array];
        if (!IsKind(list, JsonKind::kObjects))
            throw InputError(file, array, "expected an array of objects");
        for (size_t i = 0; i < list.size(); ++i) {
            JsonFields element(list[i], JsonIndexed(array, i), file);
            for (const FieldKind& f : kFieldKinds)
                if (std::strcmp(f.array, array) == 0)
                    ExpectNestedKind(file, list[i], JsonIndexed(array, i), f.field, f.kind);
            if (std::strcmp(array, "materials") == 0)
                for (const char* slot : kGltfTextureSlots)
                    for (const SlotFieldKind& f : kTextureInfoKinds)
                        ExpectNestedKind(file, list[i], JsonIndexed(array, i),
                                         std::string(slot) + f.field, f.kind);
        }
    }
    *channels = ChannelsWithNodes(root);  // animations is an array of objects by now
    CheckRequiredGltfFields(file, root);
    // tinygltf reads 5124 (a 32-bit signed integer, which glTF does not have) as an integer
    // type, and float positions stored so were read as integers.
    if (root.contains("accessors"))
        for (size_t i = 0; i < root["accessors"].size(); ++i) {
            const Json& accessor = root["accessors"][i];
            if (!accessor.contains("componentType")) continue;
            const int64_t type = accessor["componentType"].is_number_unsigned()
                                     ? int64_t(std::min<uint64_t>(
                                           accessor["componentType"].get<uint64_t>(), 1u << 20))
                                     : accessor["componentType"].get<int64_t>();
            if (type != 5120 && type != 5121 && type != 5122 && type != 5123 && type != 5125 &&
                type != 5126)
                throw InputError(file, JsonIndexed("accessors", i) + ".componentType",
                                 "must be 5120, 5121, 5122, 5123, 5125 or 5126 (glTF's component "
                                 "types), got " +
                                     std::to_string(type));
        }
    for (const char* names : {"extensionsUsed", "extensionsRequired"})
        if (root.contains(names) && !IsKind(root[names], JsonKind::kStrings))
            throw InputError(
                file, names,
                std::string("expected an array of strings, got ") + root[names].type_name());
    // Required meshopt compression leaves the buffers' own data empty (a fallback without a uri):
    // read as if uncompressed, they had failed with errors that named other fields.
    if (root.contains("extensionsRequired"))
        for (const Json& name : root["extensionsRequired"])
            if (name == "EXT_meshopt_compression" || name == "KHR_meshopt_compression")
                throw InputError(file, "extensionsRequired",
                                 name.get<std::string>() +
                                     ": the buffers are meshopt-compressed, which rtrt cannot "
                                     "decode; export the file uncompressed (gltfpack without -c "
                                     "or -cc) or with Draco (KHR_draco_mesh_compression)");
    // glTF's minimums for the sizes and offsets tinygltf reads without checking them (a negative
    // byteOffset was read as 0).
    for (const FieldMinimum& m : kFieldMinimums) {
        if (!root.contains(m.array)) continue;
        const Json& list = root[m.array];
        for (size_t i = 0; i < list.size(); ++i)
            if (list[i].contains(m.field) && !list[i][m.field].is_number_unsigned() &&
                list[i][m.field].get<int64_t>() < m.minimum)
                throw InputError(file, JsonIndexed(m.array, i) + "." + m.field,
                                 "must be at least " + std::to_string(m.minimum) + ", got " +
                                     std::to_string(list[i][m.field].get<int64_t>()));
    }
    if (root.contains("bufferViews"))
        for (size_t i = 0; i < root["bufferViews"].size(); ++i) {
            const Json& view = root["bufferViews"][i];
            // 0 is below glTF's minimum but common in exported files; tinygltf and rtrt's
            // accessors read it as tightly packed.
            if (!view.contains("byteStride") || view["byteStride"] == 0) continue;
            const int64_t stride =
                view["byteStride"].is_number_unsigned()
                    ? int64_t(std::min<uint64_t>(view["byteStride"].get<uint64_t>(), 1u << 20))
                    : view["byteStride"].get<int64_t>();
            if (stride < 4 || stride > 252 || stride % 4 != 0)
                throw InputError(
                    file, JsonIndexed("bufferViews", i) + ".byteStride",
                    "must be a multiple of 4 from 4 to 252, got " + std::to_string(stride));
        }
    if (root.contains("asset") && root["asset"].is_object() && root["asset"].contains("version") &&
        root["asset"]["version"].is_string()) {
        const std::string version = root["asset"]["version"].get<std::string>();
        if (version.rfind("2.", 0) != 0)
            throw InputError(file, "asset.version",
                             "rtrt reads glTF 2.x, the file says \"" + version + "\"");
    }
    // tinygltf reads an aspectRatio of 0 as absent; glTF requires it to be greater than 0.
    if (root.contains("cameras"))
        for (size_t i = 0; i < root["cameras"].size(); ++i) {
            const Json& camera = root["cameras"][i];
            if (!camera.contains("perspective") || !camera["perspective"].is_object()) continue;
            const Json& perspective = camera["perspective"];
            if (perspective.contains("aspectRatio") &&
                !(perspective["aspectRatio"].is_number() &&
                  perspective["aspectRatio"].get<double>() > 0.0))
                throw InputError(file, JsonIndexed("cameras", i) + ".perspective.aspectRatio",
                                 "must be a number greater than 0");
        }
    const std::vector<bool> used = UsedImages(root);
    for (const char* array : {"buffers", "images"}) {
        if (!root.contains(array) || !root[array].is_array()) continue;
        const Json& list = root[array];
        for (size_t i = 0; i < list.size(); ++i) {
            if (!list[i].is_object() || !list[i].contains("uri") || !list[i]["uri"].is_string())
                continue;
            const std::string uri = list[i]["uri"].get<std::string>();
            const std::string field = JsonIndexed(array, i);
            // An image rtrt will not decode may be missing (or a format it cannot read), but
            // one that is there must be a file: tinygltf opens it to see that it exists, which
            // waits for ever on a FIFO.
            if (std::strcmp(array, "images") == 0 && !used[i]) {
                std::error_code ec;
                const fs::path path = fs::path(dir.empty() ? "." : dir) / DecodeGltfUri(uri);
                if (uri.rfind("data:", 0) != 0 && fs::exists(path, ec) &&
                    !fs::is_regular_file(path, ec))
                    throw InputError(file, field + ".uri",
                                     "\"" + path.string() +
                                         "\" is not a regular file (a folder, device or FIFO)");
                continue;
            }
            if (uri.rfind("data:", 0) == 0) {
                CheckDataUriType(file, field, uri);
                if (std::strcmp(array, "buffers") == 0) CheckBufferDataUri(file, field, list[i]);
                continue;
            }
            const fs::path relative = DecodeGltfUri(uri);
            if (relative.is_absolute())
                throw InputError(file, field + ".uri",
                                 "\"" + uri +
                                     "\" is an absolute path; a glTF file names its files "
                                     "relative to itself");
            std::error_code ec;
            const fs::path path = fs::path(dir.empty() ? "." : dir) / relative;
            if (!fs::exists(path, ec))
                throw InputError(file, field + ".uri",
                                 ec ? "\"" + path.string() + "\": " + ec.message()  // a link loop
                                    : "no such file \"" + path.string() + "\"");
            if (!fs::is_regular_file(path, ec))
                throw InputError(
                    file, field + ".uri",
                    "\"" + path.string() + "\" is not a regular file (a folder, device or FIFO)");
            // tinygltf reads a buffer's file whole, then requires its byteLength: a 2 GiB file
            // named for 36 bytes was read (and copied) before that was found.
            const uint64_t size = fs::file_size(path, ec);
            if (std::strcmp(array, "buffers") == 0 && !ec && list[i].contains("byteLength") &&
                list[i]["byteLength"].is_number_integer() &&
                size != list[i]["byteLength"].get<uint64_t>())
                throw InputError(file, field + ".byteLength",
                                 "is " + list[i]["byteLength"].dump() + ", but \"" + path.string() +
                                     "\" holds " + std::to_string(size) +
                                     " bytes; they must be equal");
        }
    }
    CheckGltfReferences(file, root);
    return used;
}

std::string ReadWholeFile(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(path, "", "no such file");
    if (fs::is_directory(path, ec)) throw InputError(path, "", "is a directory, not a glTF file");
    return ReadAssetFile(path);
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
                              fs::path(file).parent_path().string(), &out.firstAnimationChannels);
    return out;
}

}  // namespace rtrt
