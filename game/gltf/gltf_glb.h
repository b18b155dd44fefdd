#pragma once
// The GLB container (glTF 2.0, "Binary glTF Layout"): its JSON and BIN chunks taken apart and put
// back together, for the steps that rewrite a file's JSON before tinygltf reads it.
#include <cstdint>
#include <string>

namespace rtrt {

struct GlbChunks {
    std::string json, bin;
    bool hasBin = false;
    // The chunk after the JSON is of a type glTF does not define (which readers must ignore, and
    // tinygltf 2.7 refuses there).
    bool unknownAfterJson = false;
};

// The little-endian 32-bit word at byte AT.
uint32_t GlbWord(const std::string& bytes, size_t at);

// The chunks of a GLB that ReadCheckedGltf has checked.
GlbChunks SplitGlb(const std::string& bytes);

// A GLB of a JSON chunk and, with withBin, a BIN chunk, each padded as the layout asks (spaces,
// zeros).
std::string MakeGlb(std::string json, std::string bin, bool withBin = true);

}  // namespace rtrt
