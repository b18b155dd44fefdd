#include "game/gltf/gltf_glb.h"

#include <cstring>

namespace rtrt {
namespace {

constexpr uint32_t kChunkJson = 0x4E4F534Au;
constexpr uint32_t kChunkBin = 0x004E4942u;

}  // namespace

uint32_t GlbWord(const std::string& bytes, size_t at) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
}

GlbChunks SplitGlb(const std::string& bytes) {
    GlbChunks out;
    const uint32_t jsonLength = GlbWord(bytes, 12);
    out.json = bytes.substr(20, jsonLength);
    const size_t at = 20 + size_t(jsonLength);
    if (bytes.size() - at >= 8 && GlbWord(bytes, at + 4) == kChunkBin) {
        out.bin = bytes.substr(at + 8, GlbWord(bytes, at));
        out.hasBin = true;
    } else if (bytes.size() - at >= 8) {
        out.unknownAfterJson = true;
    }
    return out;
}

std::string MakeGlb(std::string json, std::string bin, bool withBin) {
    while (json.size() % 4) json += ' ';
    while (bin.size() % 4) bin += '\0';
    std::string out;
    auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    out += "glTF";
    u32(2);
    u32(uint32_t(12 + 8 + json.size() + (withBin ? 8 + bin.size() : 0)));
    u32(uint32_t(json.size()));
    u32(kChunkJson);
    out += json;
    if (!withBin) return out;
    u32(uint32_t(bin.size()));
    u32(kChunkBin);
    out += bin;
    return out;
}

}  // namespace rtrt
