#pragma once
// Triangle models as BLASes, built once: a mesh file (.obj, .ply, .ply.gz) is parsed and its BVH
// built only when the BLAS cache has no up-to-date .rtmodel of it; an .rtmodel file is read as
// it is. The cache lives in $RTRT_CACHE_DIR, else $XDG_CACHE_HOME/rtrt/blas, else
// ~/.cache/rtrt/blas (RTRT_CACHE_DIR=off turns it off). An entry is named after the source's
// path and the builder; it is used only when its key (the source's content hash, the builder
// and its options, kRtModelRevision) matches, so edited sources, stale or corrupt entries are
// rebuilt, never trusted.
#include <string>

#include "engine/bvh/blas/rtmodel.h"

namespace rtrt {

struct MeshModel {
    Blas blas;
    RtModelInfo info;
    enum class Origin { kBuilt, kCache, kRtModelFile } origin = Origin::kBuilt;
    std::string cachePath;  // the cache entry used or written; "" if none
    double hashMs = 0.0, parseMs = 0.0, buildMs = 0.0, readMs = 0.0;
};

// Parses a mesh file and builds its BLAS (no cache): what `rtrt convert` stores. sourceHash goes
// into the key; progress, if given, is told before each stage ("parse", "build").
MeshModel BuildMeshModel(const std::string& path, const BvhBuildOptions& options,
                         uint64_t sourceHash, void (*progress)(const char* stage) = nullptr);

// The model in PATH: an .rtmodel is read (its own builder stands, whatever OPTIONS say); a mesh
// comes from the cache or is built and then cached. Cache failures only cost the rebuild (a
// warning on stderr when an entry cannot be written). Throws InputError for a bad model file.
MeshModel LoadMeshModel(const std::string& path, const BvhBuildOptions& options);

// The cache folder, or "" when the cache is off.
std::string BlasCacheDir();

}  // namespace rtrt
