#include "game/assets/model_cache.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/core/timer.h"
#include "game/assets/mesh_io.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

// One entry per source file and builder: "dragon_vrip.ply.gz-<hash of its absolute path>-binned".
// A changed source then overwrites its entry instead of leaving the old one behind.
std::string CachePath(const std::string& dir, const std::string& source, BvhBuilder builder) {
    std::error_code ec;
    fs::path absolute = fs::weakly_canonical(fs::absolute(source), ec);
    if (ec) absolute = fs::absolute(source);
    const std::string where = absolute.string();
    // The name is for people reading the folder (the hash of the path tells entries apart),
    // shortened so that the entry's name stays within a file system's 255 bytes.
    const std::string name = absolute.filename().string().substr(0, 128);
    return dir + "/" + name + "-" + HexDigest(HashBytes(where.data(), where.size())) + "-" +
           std::string(BuilderName(builder)) + ".rtmodel";
}

// The entry's BLAS if its header carries KEY and the whole file validates; false otherwise.
bool ReadCacheEntry(const std::string& path, const RtModelKey& key, MeshModel* model) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return false;
    try {
        if (!(ReadRtModelInfo(path).key == key)) return false;  // stale: rebuilt and replaced
        Stopwatch timer;
        model->blas = ReadRtModel(path, &model->info);
        model->readMs = timer.Milliseconds();
        return true;
    } catch (const InputError& e) {
        // An entry of another format version was written by another rtrt: stale, not bad.
        if (e.Field() != "header.version")
            std::fprintf(stderr, "rtrt: warning: rebuilding a bad cache entry: %s\n", e.what());
        return false;
    }
}

// A cache that cannot be written costs only time: the work goes on, with one warning per process.
// Whether the entry was written.
bool WriteCacheEntry(const std::string& dir, const MeshModel& model) {
    std::string why;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) {
        why = dir + ": cannot create the folder: " + ec.message();
    } else {
        try {
            WriteRtModel(model.cachePath, model.blas, model.info);
            return true;
        } catch (const std::exception& e) {
            why = e.what();
        }
    }
    static std::atomic<bool> warned{false};
    if (!warned.exchange(true))
        std::fprintf(stderr,
                     "rtrt: warning: BLAS cache not written (%s); going on without (set "
                     "RTRT_CACHE_DIR to a writable folder, or to off)\n",
                     why.c_str());
    return false;
}

}  // namespace

std::string BlasCacheDir() {
    if (const char* dir = std::getenv("RTRT_CACHE_DIR"); dir && *dir)
        return std::string(dir) == "off" ? std::string() : std::string(dir);
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return std::string(xdg) + "/rtrt/blas";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::string(home) + "/.cache/rtrt/blas";
    return "";
}

MeshModel BuildMeshModel(const std::string& path, const BvhBuildOptions& options,
                         uint64_t sourceHash, void (*progress)(const char* stage)) {
    MeshModel model;
    if (progress) progress("parse");
    Stopwatch timer;
    uint64_t fileVertices = 0;
    const TriangleMesh mesh = LoadMesh(path, &fileVertices);
    model.parseMs = timer.Milliseconds();
    if (progress) progress("build");
    timer.Restart();
    model.blas = BuildTriangleBlas(mesh, options);
    model.buildMs = timer.Milliseconds();
    model.info.key = MakeRtModelKey(sourceHash, options);
    model.info.sourceVertexCount = uint32_t(fileVertices);
    model.info.sourceBounds = mesh.Bounds();
    model.info.sahCost = SahCost(model.blas.nodes);
    return model;
}

MeshModel LoadMeshModel(const std::string& path, const BvhBuildOptions& options) {
    // Read from its cache or not, the file is the scene's (a farm job's checksum covers it).
    RememberAssetFile(path);
    if (IsRtModelPath(path)) {
        MeshModel model;
        Stopwatch timer;
        model.blas = ReadRtModel(path, &model.info);
        model.readMs = timer.Milliseconds();
        model.origin = MeshModel::Origin::kRtModelFile;
        return model;
    }
    const std::string dir = BlasCacheDir();
    std::error_code ec;
    if (dir.empty() || !fs::is_regular_file(path, ec)) return BuildMeshModel(path, options, 0);

    Stopwatch timer;
    const uint64_t sourceHash = HashFile(path);
    const double hashMs = timer.Milliseconds();
    const RtModelKey key = MakeRtModelKey(sourceHash, options);
    const std::string cachePath = CachePath(dir, path, options.builder);
    MeshModel model;
    if (ReadCacheEntry(cachePath, key, &model)) {
        model.origin = MeshModel::Origin::kCache;
        model.cachePath = cachePath;
    } else {
        model = BuildMeshModel(path, options, sourceHash);
        model.cachePath = cachePath;
        if (!WriteCacheEntry(dir, model)) model.cachePath.clear();
    }
    model.hashMs = hashMs;
    return model;
}

}  // namespace rtrt
