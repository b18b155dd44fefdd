#pragma once
// The byte layout of .rtmodel files (rtmodel.h says what they are). Separate from the reader so
// that tests and fuzzers can craft files field by field.
#include <cstddef>
#include <cstdint>

#include "engine/bvh/blas/blas.h"
#include "engine/core/content_hash.h"

namespace rtrt::rtmodel {

inline constexpr char kMagic[8] = {'R', 'T', 'M', 'O', 'D', 'E', 'L', '\0'};
inline constexpr uint64_t kAlignment = 64;

enum Section {
    kNodes,
    kNodes4,
    kTriangles,
    kNormals,
    kSpheres,
    kPrimIds,
    kUvs,
    kColors,
    kSectionCount
};
inline constexpr const char* kSectionNames[kSectionCount] = {
    "nodes", "nodes4", "triangles", "normals", "spheres", "primIds", "uvs", "colors"};
inline constexpr uint64_t kElementBytes[kSectionCount] = {
    sizeof(BvhNode), sizeof(Bvh4Node), sizeof(Triangle),    sizeof(TriangleNormals),
    sizeof(Sphere),  sizeof(uint32_t), sizeof(TriangleUvs), sizeof(TriangleColors)};

struct RtModelHeader {
    char magic[8];
    uint32_t version;
    uint32_t headerBytes;
    uint32_t kind;     // GeometryKind
    uint32_t builder;  // BvhBuilder
    uint32_t maxLeafSize;
    uint32_t binCount;
    uint32_t revision;
    uint32_t sourceVertexCount;
    uint64_t sourceHash;
    uint64_t counts[kSectionCount];
    float sourceBoundsMin[3];
    float sourceBoundsMax[3];
    float sahCost;
    uint32_t reserved0;
    uint64_t fileBytes;
    uint64_t payloadChecksum;  // PayloadChecksum of the sections' hashes
    uint8_t reserved[88];
    uint64_t headerChecksum;  // HashBytes of the header's first 248 bytes
};
static_assert(sizeof(RtModelHeader) == 256, "the header is 256 bytes, a multiple of 64");
inline constexpr size_t kHeaderHashedBytes = offsetof(RtModelHeader, headerChecksum);

inline uint64_t AlignUp(uint64_t n) { return (n + kAlignment - 1) / kAlignment * kAlignment; }

// Where each section starts and where the file ends, from the counts. The caller has bounded
// every count by the file size, so nothing here overflows.
struct Layout {
    uint64_t offset[kSectionCount];
    uint64_t fileBytes;
};
inline Layout LayoutOf(const uint64_t counts[kSectionCount]) {
    Layout layout;
    uint64_t at = sizeof(RtModelHeader);
    for (int s = 0; s < kSectionCount; ++s) {
        layout.offset[s] = at;
        at = AlignUp(at + counts[s] * kElementBytes[s]);
    }
    layout.fileBytes = at;
    return layout;
}

// Each section is hashed with its padding (HashBytes of [offset, next offset)), so that sections
// can be read and hashed in parallel; the payload checksum is the hash of those hashes.
inline uint64_t PayloadChecksum(const uint64_t (&sectionHashes)[kSectionCount]) {
    return HashBytes(sectionHashes, sizeof(sectionHashes));
}

// The payload checksum of a whole file held in memory (tests and tools craft files this way).
inline uint64_t PayloadChecksumOf(const char* file, const Layout& layout) {
    uint64_t hashes[kSectionCount];
    for (int s = 0; s < kSectionCount; ++s) {
        const uint64_t end = s + 1 < kSectionCount ? layout.offset[s + 1] : layout.fileBytes;
        hashes[s] = HashBytes(file + layout.offset[s], end - layout.offset[s]);
    }
    return PayloadChecksum(hashes);
}

// Recomputes headerChecksum after the header's other fields changed.
inline void SealHeader(RtModelHeader& h) { h.headerChecksum = HashBytes(&h, kHeaderHashedBytes); }

}  // namespace rtrt::rtmodel
