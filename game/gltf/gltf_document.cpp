#include "game/gltf/gltf_document.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "game/gltf/gltf_draco.h"
#include "game/gltf/gltf_glb.h"
#include "game/gltf/gltf_image_loader.h"
#include "game/gltf/gltf_precheck.h"
#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

// tinygltf's messages can span lines and start with "Error: "; the CLI prints one line.
std::string OneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    if (text.rfind("Error: ", 0) == 0) text = text.substr(7);
    return text.empty() ? "tinygltf could not load the file" : text;
}

// tinygltf 2.7 (Debian's) reports as errors two fields glTF 2.0 makes optional: a skin's
// inverseBindMatrices (identity matrices, which gltf_skins.cpp supplies; it still loads the skin)
// and an animation channel's target.node (an extension may name the target instead; it drops the
// channel). Their messages are dropped so that such a file loads (*skippedChannels counts the
// channels); every other message stays.
std::string WithoutOptionalFieldErrors(const std::string& err, int* skippedChannels) {
    static const std::string kSkinMatrices = "'inverseBindMatrices' property is missing in Skin.";
    static const std::string kChannelNode = "'node' property is missing.";
    static const std::string kChannelNodeAgain =
        "`node` field is missing in animation.channels.target";
    std::string out;
    size_t begin = 0;
    *skippedChannels = 0;
    while (begin < err.size()) {
        size_t end = err.find('\n', begin);
        if (end == std::string::npos) end = err.size();
        const std::string line = err.substr(begin, end - begin);
        if (line == kChannelNodeAgain) ++*skippedChannels;
        if (line != kSkinMatrices && line != kChannelNode && line != kChannelNodeAgain)
            out += line + "\n";
        begin = end + 1;
    }
    return out;
}

// Whether tinygltf 2.7, which decodes a uri as an HTML form does ('+' a space; '%' and the two
// characters after it one byte, hex digits or not), would read another path from URI than RFC
// 3986's, which glTF uses and DecodeGltfUri reads.
bool TinygltfMisreads(const std::string& uri) {
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') return true;
        if (uri[i] == '%' && !(i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) &&
                               std::isxdigit(uint8_t(uri[i + 2]))))
            return true;
    }
    return false;
}

std::string PercentEncoded(const std::string& path) {
    static const char kHex[] = "0123456789ABCDEF";
    std::string out;
    for (const char c : path) {
        const uint8_t u = uint8_t(c);
        if (std::isalnum(u) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
            out += c;
        } else {
            out += '%';
            out += kHex[u >> 4];
            out += kHex[u & 15];
        }
    }
    return out;
}

// The file (BYTES, a GLB when BINARY) as tinygltf 2.7 reads it as glTF means it: every external
// buffer and image uri that it would misread ("a+b.bin", "50%.png") percent-encoded, so that it
// opens the file the uri names (a '+' is a plus in a uri, not a space), and a GLB without the
// chunk of unknown type that follows its JSON; nullopt when nothing needs it.
std::optional<std::string> AsTinygltfReadsIt(const std::string& file, const std::string& bytes,
                                             bool binary) {
    std::optional<GlbChunks> glb;
    if (binary) glb = SplitGlb(bytes);
    const std::string& json = binary ? glb->json : bytes;
    const bool dropChunk = binary && glb->unknownAfterJson;
    if (!dropChunk && json.find_first_of("+%") == std::string::npos) return std::nullopt;
    Json root = ParseJson(json, file, DuplicateKeys::kLastWins);
    bool changed = false;
    for (const char* array : {"buffers", "images"}) {
        if (!root.contains(array) || !root[array].is_array()) continue;
        for (Json& element : root[array]) {
            if (!element.is_object() || !element.contains("uri") || !element["uri"].is_string())
                continue;
            const std::string uri = element["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0 || !TinygltfMisreads(uri)) continue;
            element["uri"] = PercentEncoded(DecodeGltfUri(uri));
            changed = true;
        }
    }
    if (!changed && !dropChunk) return std::nullopt;
    return binary ? MakeGlb(root.dump(), glb->bin, glb->hasBin) : root.dump();
}

// tinygltf's reader of external buffers and images: rtrt's, so that a uri naming a device or a
// FIFO is refused instead of read for ever or waited on, and one over 2 GiB before it is read.
bool ReadExternalFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                      void*) {
    try {
        const std::string bytes = ReadAssetFile(path);
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const InputError& e) {
        if (err) *err += "\"" + path + "\": " + e.Reason();
        return false;
    }
}

// tinygltf's check that a file exists, without opening it: its own opens the file, which waits
// for ever on a FIFO.
bool IsRegularFile(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}

}  // namespace

GltfDocument::GltfDocument(std::string file) : file_(std::move(file)) {
    GltfFileBytes checked = ReadCheckedGltf(file_);
    firstAnimationChannels_ = std::move(checked.firstAnimationChannels);
    const std::string dir = std::filesystem::path(file_).parent_path().string();
    const std::optional<DracoDecoded> draco =
        DecodeDracoPrimitives(file_, checked.bytes, checked.binary, dir);
    const bool binary = draco ? true : checked.binary;
    const std::optional<std::string> withUris =
        AsTinygltfReadsIt(file_, draco ? draco->glb : checked.bytes, binary);
    const std::string& bytes = withUris ? *withUris : draco ? draco->glb : checked.bytes;
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&IsRegularFile, &tinygltf::ExpandFilePath, &ReadExternalFile,
                           &tinygltf::WriteWholeFile, nullptr});
    GltfImageFailure imageFailure;
    imageFailure.used = &checked.imageUsed;
    imageFailure.file = file_;
    InstallGltfImageLoader(loader, &imageFailure);
    std::string err, warn;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model_, &err, &warn, data, unsigned(bytes.size()),
                                             dir.empty() ? "." : dir)
               : loader.LoadASCIIFromString(&model_, &err, &warn, bytes.data(),
                                            unsigned(bytes.size()), dir.empty() ? "." : dir);
    int skippedChannels = 0;
    err = WithoutOptionalFieldErrors(err, &skippedChannels);
    if (imageFailure.fatal) std::rethrow_exception(imageFailure.fatal);
    if (imageFailure.index >= 0)
        Fail(JsonIndexed("images", size_t(imageFailure.index)), OneLine(imageFailure.reason));
    if (!ok || !err.empty()) Fail("", OneLine(err));
    if (skippedChannels > 0)
        Warn("animation-target",
             std::to_string(skippedChannels) +
                 " animation channel(s) without target.node (an extension's target, as "
                 "KHR_animation_pointer's) are not played");
    if (draco)
        Warn("draco", std::to_string(draco->primitives) +
                          " Draco-compressed primitive(s) decoded with libdraco "
                          "(KHR_draco_mesh_compression)");
    for (int index : imageFailure.skipped)
        Warn("image-unused", JsonIndexed("images", size_t(index)) +
                                 ": no texture's source names it (an extension's image, as "
                                 "KHR_texture_basisu's KTX2, or none); it is not decoded");
}

std::string GltfDocument::FirstAnimationChannel(size_t c) const {
    return JsonIndexed("animations[0].channels",
                       c < firstAnimationChannels_.size() ? firstAnimationChannels_[c] : c);
}

std::string CountGltfTexels(GltfImageFailure* failure, int width, int height) {
    const uint64_t texels = uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0));
    if (texels > kMaxGltfFileTexels - failure->texels)
        return std::to_string(width) + " x " + std::to_string(height) +
               " texels would take the file's images past what rtrt reads (2^30 texels "
               "together)";
    failure->texels += texels;
    return "";
}

bool DecodeGltfImage(GltfImageFailure* failure, int index) {
    if (!failure->used || index < 0 || size_t(index) >= failure->used->size() ||
        (*failure->used)[size_t(index)])
        return true;
    failure->skipped.push_back(index);
    return false;
}

void GltfDocument::Fail(const std::string& field, const std::string& reason) const {
    throw InputError(file_, field, reason);
}

void GltfDocument::Warn(const std::string& kind, const std::string& text) {
    if (!warned_.insert(kind).second) return;
    std::fprintf(stderr, "rtrt: warning: %s: %s\n", file_.c_str(), text.c_str());
}

}  // namespace rtrt
