#pragma once
// .rtmodel files: a BLAS stored in the layout the tracer uses, so that loading is one read per
// array plus validation, and no BVH build. Little-endian, every array on a 64-byte boundary:
//
//   RtModelHeader (256 bytes) | nodes | nodes4 | triangles | normals | spheres | primIds | uvs
//   | colors
//
// The header carries the format version, the array counts, the file size, XXH3-64 checksums of
// itself and of everything after it, the SAH cost, and the key of the source (content hash,
// builder and its options) by which a cache decides whether a file is up to date.
#include <cstdint>
#include <string>

#include "engine/bvh/blas/blas.h"

namespace rtrt {

// Version 2 added the uvs section (per-triangle texture coordinates); version 3 packs the
// normals (three 32-bit octahedral normals per triangle, packed_normal.h); version 4 added the
// colors section (per-vertex colours of each triangle, TriangleColors).
inline constexpr uint32_t kRtModelVersion = 4;
// Bump when a builder or a mesh loader changes its output for the same input: cached files made
// before then no longer match their key and are rebuilt. 2: sourceBounds of the vertices the
// triangles use. 3: concave polygons ear-clipped, PLY triangle strips, file normals kept per
// corner, an OBJ's source vertices its `v` statements.
inline constexpr uint32_t kRtModelRevision = 3;

// What a BLAS was built from. A cached file is up to date when its key equals the one wanted.
struct RtModelKey {
    uint64_t sourceHash = 0;  // HashFile of the source model (0: not from a file)
    BvhBuilder builder = BvhBuilder::kBinnedSah;
    uint32_t maxLeafSize = 8;
    uint32_t binCount = 32;
    uint32_t revision = kRtModelRevision;

    bool operator==(const RtModelKey&) const = default;
};
RtModelKey MakeRtModelKey(uint64_t sourceHash, const BvhBuildOptions& options);

// What the header says besides the arrays.
struct RtModelInfo {
    RtModelKey key;
    uint32_t version = kRtModelVersion;
    uint32_t sourceVertexCount = 0;
    Aabb sourceBounds;  // of the source vertices triangles use: what FitMesh centres and scales
    float sahCost = 0.0f;
    uint64_t fileBytes = 0;
};

// Writes through a temporary file in the same folder and a rename, so that readers never see a
// partial file. Throws InputError when the folder does not exist, OutputError (the system's reason)
// when a write, flush, close or rename fails; no temporary is left behind.
void WriteRtModel(const std::string& path, const Blas& blas, const RtModelInfo& info);

// Reads and validates a file: header fields, sizes against the file length, both checksums, then
// the structure (CheckBlas). Throws InputError (file, field, reason) for anything wrong.
Blas ReadRtModel(const std::string& path, RtModelInfo* info = nullptr);

// The validated header alone (no arrays read or checked).
RtModelInfo ReadRtModelInfo(const std::string& path);

// True when PATH ends in .rtmodel (any case).
bool IsRtModelPath(const std::string& path);

}  // namespace rtrt
