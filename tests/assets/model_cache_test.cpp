// The BLAS cache: a mesh is built once and then read; edited sources, other builders and corrupt
// entries are rebuilt; a converted model renders exactly like a freshly built one.
#include "game/assets/model_cache.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "engine/bvh/blas/rtmodel.h"
#include "engine/bvh/blas/rtmodel_format.h"
#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/render_rt/renderer.h"
#include "game/assets/mesh_io.h"
#include "game/assets/procedural_shapes.h"
#include "game/scene/paper_scene.h"
#include "game/scene/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

template <typename A, typename B>
bool SameBytes(const A& a, const B& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

void ExpectIdentical(const Blas& a, const Blas& b) {
    EXPECT_TRUE(SameBytes(a.nodes, b.nodes));
    EXPECT_TRUE(SameBytes(a.nodes4, b.nodes4));
    EXPECT_TRUE(SameBytes(a.triangles, b.triangles));
    EXPECT_TRUE(SameBytes(a.normals, b.normals));
    EXPECT_TRUE(SameBytes(a.primIds, b.primIds));
}

const char* kQuadObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\nf 1 2 5\n";

class ModelCacheTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("rtrt_model_cache_" + std::to_string(getpid()) + "_" + info->name());
        fs::create_directories(dir_ / "cache");
        const char* old = std::getenv("RTRT_CACHE_DIR");
        oldCache_ = old ? old : "";
        setenv("RTRT_CACHE_DIR", (dir_ / "cache").c_str(), 1);
    }
    void TearDown() override {
        setenv("RTRT_CACHE_DIR", oldCache_.c_str(), 1);
        fs::remove_all(dir_);
    }
    std::string Write(const std::string& name, const std::string& text) {
        const std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    size_t CacheEntries() const {
        return size_t(std::distance(fs::directory_iterator(dir_ / "cache"), {}));
    }

    fs::path dir_;
    std::string oldCache_;
};

TEST_F(ModelCacheTest, BuildsOnceThenReads) {
    const std::string obj = Write("quad.obj", kQuadObj);
    const MeshModel first = LoadMeshModel(obj, {});
    EXPECT_EQ(first.origin, MeshModel::Origin::kBuilt);
    ASSERT_TRUE(fs::exists(first.cachePath));
    EXPECT_EQ(fs::path(first.cachePath).parent_path(), dir_ / "cache");
    const MeshModel second = LoadMeshModel(obj, {});
    EXPECT_EQ(second.origin, MeshModel::Origin::kCache);
    EXPECT_EQ(second.cachePath, first.cachePath);
    EXPECT_EQ(second.info.key, first.info.key);
    EXPECT_EQ(second.info.key.sourceHash, HashFile(obj));
    EXPECT_EQ(second.info.sourceVertexCount, 5u);
    ExpectIdentical(first.blas, second.blas);
    EXPECT_EQ(CacheEntries(), 1u);
}

// A source whose name is as long as a file system allows is cached too (its entry's name had
// passed 255 bytes, and every run rebuilt it with a warning).
TEST_F(ModelCacheTest, ASourceOfTheLongestNameIsCached) {
    const std::string obj = Write(std::string(240, 'q') + ".obj", kQuadObj);
    testing::internal::CaptureStderr();
    EXPECT_EQ(LoadMeshModel(obj, {}).origin, MeshModel::Origin::kBuilt);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(LoadMeshModel(obj, {}).origin, MeshModel::Origin::kCache);
}

TEST_F(ModelCacheTest, AnEditedSourceIsRebuiltInPlace) {
    const std::string obj = Write("quad.obj", kQuadObj);
    const MeshModel before = LoadMeshModel(obj, {});
    Write("quad.obj", std::string(kQuadObj) + "v 0 0 2\nf 1 2 6\n");
    const MeshModel after = LoadMeshModel(obj, {});
    EXPECT_EQ(after.origin, MeshModel::Origin::kBuilt);
    EXPECT_EQ(after.blas.PrimCount(), before.blas.PrimCount() + 1);
    EXPECT_EQ(after.cachePath, before.cachePath);
    EXPECT_EQ(CacheEntries(), 1u);
    EXPECT_EQ(LoadMeshModel(obj, {}).origin, MeshModel::Origin::kCache);
}

TEST_F(ModelCacheTest, EachBuilderHasItsOwnEntry) {
    const std::string obj = Write("quad.obj", kQuadObj);
    BvhBuildOptions sweep;
    sweep.builder = BvhBuilder::kSweepSah;
    LoadMeshModel(obj, {});
    const MeshModel s = LoadMeshModel(obj, sweep);
    EXPECT_EQ(s.origin, MeshModel::Origin::kBuilt);
    EXPECT_EQ(s.info.key.builder, BvhBuilder::kSweepSah);
    EXPECT_EQ(CacheEntries(), 2u);
}

TEST_F(ModelCacheTest, ACorruptEntryIsRebuiltNotTrusted) {
    const std::string obj = Write("quad.obj", kQuadObj);
    const MeshModel first = LoadMeshModel(obj, {});
    {
        std::fstream f(first.cachePath, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(300);
        f.put('\x7f');
    }
    EXPECT_THROW(ReadRtModel(first.cachePath), InputError);
    const MeshModel again = LoadMeshModel(obj, {});
    EXPECT_EQ(again.origin, MeshModel::Origin::kBuilt);
    ExpectIdentical(first.blas, again.blas);
    EXPECT_NO_THROW(ReadRtModel(first.cachePath));  // rewritten
}

// An entry written by an rtrt of another format version (version 1, before uvs) is stale: rebuilt
// silently, like an entry of another key.
TEST_F(ModelCacheTest, AnOlderFormatVersionIsRebuiltSilently) {
    const std::string obj = Write("quad.obj", kQuadObj);
    const MeshModel first = LoadMeshModel(obj, {});
    {
        std::fstream f(first.cachePath, std::ios::in | std::ios::out | std::ios::binary);
        rtmodel::RtModelHeader h;
        f.read(reinterpret_cast<char*>(&h), sizeof(h));
        h.version = 1;
        rtmodel::SealHeader(h);
        f.seekp(0);
        f.write(reinterpret_cast<const char*>(&h), sizeof(h));
    }
    ::testing::internal::CaptureStderr();
    const MeshModel again = LoadMeshModel(obj, {});
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(again.origin, MeshModel::Origin::kBuilt);
    EXPECT_EQ(ReadRtModelInfo(first.cachePath).version, kRtModelVersion);  // rewritten
}

TEST_F(ModelCacheTest, TheCacheCanBeTurnedOff) {
    setenv("RTRT_CACHE_DIR", "off", 1);
    const std::string obj = Write("quad.obj", kQuadObj);
    EXPECT_EQ(LoadMeshModel(obj, {}).origin, MeshModel::Origin::kBuilt);
    EXPECT_EQ(LoadMeshModel(obj, {}).origin, MeshModel::Origin::kBuilt);
    EXPECT_EQ(CacheEntries(), 0u);
}

TEST_F(ModelCacheTest, AnUnwritableCacheOnlyCostsTheRebuild) {
    const std::string blocker = Write("file", "not a folder");
    setenv("RTRT_CACHE_DIR", (blocker + "/cache").c_str(), 1);
    const std::string obj = Write("quad.obj", kQuadObj);
    const MeshModel model = LoadMeshModel(obj, {});
    EXPECT_EQ(model.blas.PrimCount(), 3u);
    // Nothing was written, so the model names no cache entry (`rtrt info` said "cached as").
    EXPECT_EQ(model.origin, MeshModel::Origin::kBuilt);
    EXPECT_EQ(model.cachePath, "");
}

TEST_F(ModelCacheTest, BadMeshesAreStillInputErrors) {
    EXPECT_THROW(LoadMeshModel(Write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n"), {}),
                 InputError);
    EXPECT_THROW(LoadMeshModel((dir_ / "missing.obj").string(), {}), InputError);
    EXPECT_EQ(CacheEntries(), 0u);
}

// FitBlas moves the built BLAS exactly as FitMesh moves the mesh: the same vertices, and boxes
// that are exactly the bounds of what they hold.
TEST_F(ModelCacheTest, FitBlasMatchesFitMesh) {
    TriangleMesh mesh = test::RandomTriangles(3000, 11);
    mesh.positions.push_back(vec3(4.0f, -3.0f, 2.0f));  // an unused vertex still counts for fit
    Blas blas = BuildTriangleBlas(mesh);
    FitBlas(blas, mesh.Bounds(), 5.0f);
    FitMesh(mesh, 5.0f);
    std::vector<Aabb> slotBounds(blas.PrimCount());
    for (uint32_t slot = 0; slot < blas.PrimCount(); ++slot) {
        const glm::uvec3 idx = mesh.indices[blas.primIds[slot]];
        ASSERT_EQ(blas.triangles[slot].v0, mesh.positions[idx.x]);
        ASSERT_EQ(blas.triangles[slot].v1, mesh.positions[idx.y]);
        ASSERT_EQ(blas.triangles[slot].v2, mesh.positions[idx.z]);
        slotBounds[slot] = blas.triangles[slot].Bounds();
    }
    AlignedVector<BvhNode> refit = blas.nodes;
    Refit(refit, slotBounds);
    for (size_t i = 2; i < refit.size(); ++i) {
        ASSERT_EQ(refit[i].boundsMin, blas.nodes[i].boundsMin) << i;
        ASSERT_EQ(refit[i].boundsMax, blas.nodes[i].boundsMax) << i;
    }
    EXPECT_TRUE(SameBytes(CollapseToBvh4(blas.nodes), blas.nodes4));
}

// The convert pipeline end to end on a real model: written, read back bit for bit, and the read
// BLAS renders the paper scene pixel for pixel like the freshly built one.
TEST_F(ModelCacheTest, ConvertedDragonRendersIdentically) {
    RTRT_REQUIRE_MODEL(path, "dragon_vrip_res4.ply.gz");
    const MeshModel built = BuildMeshModel(path, {}, HashFile(path));
    const std::string out = (dir_ / "dragon.rtmodel").string();
    WriteRtModel(out, built.blas, built.info);
    const MeshModel read = LoadMeshModel(out, {});
    EXPECT_EQ(read.origin, MeshModel::Origin::kRtModelFile);
    ExpectIdentical(built.blas, read.blas);
    EXPECT_EQ(read.info.key, built.info.key);
    EXPECT_EQ(read.info.sahCost, built.info.sahCost);
    EXPECT_NEAR(read.info.sahCost, 30.37f, 0.01f);  // bench/results: dragon_res4, binned
    EXPECT_EQ(read.blas.PrimCount(), 11102u);
    EXPECT_EQ(read.info.sourceVertexCount, 5205u);

    auto render = [](Blas blas, const Aabb& sourceBounds) {
        FitBlas(blas, sourceBounds, 5.0f);
        const RenderScene scene = MakePaperScene(std::make_shared<const Blas>(std::move(blas)));
        return RenderRaw(scene, RenderSettings{160, 90, kPaperMaxDepth});
    };
    const Image a = render(built.blas, built.info.sourceBounds);
    const Image b = render(read.blas, read.info.sourceBounds);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_TRUE(SameBytes(a.pixels, b.pixels));
    size_t lit = 0;
    for (vec3 p : a.pixels) lit += p.x > 0.4f;  // the red dragon is in the picture
    EXPECT_GT(lit, 500u);
}

// Scene files load their meshes through the cache: the second load reads the entry the first
// wrote and gives the same BLAS, fitted as FitMesh would fit the mesh.
TEST_F(ModelCacheTest, SceneMeshesComeThroughTheCache) {
    Write("quad.obj", kQuadObj);
    const std::string scene = Write("scene.json", R"({
        "models": { "q": { "type": "mesh", "file": "quad.obj", "fit": 4 } },
        "instances": [ { "model": "q" } ] })");
    const LoadedScene first = LoadSceneFile(scene);
    ASSERT_EQ(CacheEntries(), 1u);
    const fs::path entry = fs::directory_iterator(dir_ / "cache")->path();
    const auto written = fs::last_write_time(entry);
    const LoadedScene second = LoadSceneFile(scene);
    EXPECT_EQ(CacheEntries(), 1u);
    EXPECT_EQ(fs::last_write_time(entry), written);  // read, not rebuilt
    ASSERT_EQ(first.scene.blases.size(), 1u);
    ExpectIdentical(*first.scene.blases[0], *second.scene.blases[0]);
    TriangleMesh mesh = LoadMesh((dir_ / "quad.obj").string());
    FitMesh(mesh, 4.0f);
    const Blas& blas = *second.scene.blases[0];
    for (uint32_t slot = 0; slot < blas.PrimCount(); ++slot)
        EXPECT_EQ(blas.triangles[slot].v1, mesh.positions[mesh.indices[blas.primIds[slot]].y]);
    EXPECT_EQ(MaxComponent(blas.bounds.Extent()), 4.0f);
}

// A vertex no triangle uses is no part of the shape: `fit` scales and centres what the triangles
// cover (a stray vertex 100 units off had shrunk the quad to a speck beside the origin), read
// through the cache or built.
TEST_F(ModelCacheTest, FitIgnoresVerticesNoTriangleUses) {
    Write("stray.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 100 100 100\nf 1 2 3\nf 1 3 4\n");
    const std::string scene = Write("stray.json", R"({
        "models": { "q": { "type": "mesh", "file": "stray.obj", "fit": 4 } },
        "instances": [ { "model": "q" } ] })");
    for (int load = 0; load < 2; ++load) {  // built, then read from the cache
        const LoadedScene loaded = LoadSceneFile(scene);
        const Aabb bounds = loaded.scene.blases.at(0)->bounds;
        EXPECT_EQ(bounds.min, vec3(-2.0f, -2.0f, 0.0f)) << load;
        EXPECT_EQ(bounds.max, vec3(2.0f, 2.0f, 0.0f)) << load;
    }
    EXPECT_EQ(CacheEntries(), 1u);
}

// The BLAS built from a coloured mesh keeps its colours, and so does the cache entry read back.
TEST_F(ModelCacheTest, VertexColoursSurviveTheCache) {
    const std::string path = Write("quad.obj",
                                   "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 1\n"
                                   "f 1 2 3 4\n");
    const MeshModel built = LoadMeshModel(path, {});
    const MeshModel cached = LoadMeshModel(path, {});
    EXPECT_EQ(built.origin, MeshModel::Origin::kBuilt);
    EXPECT_EQ(cached.origin, MeshModel::Origin::kCache);
    ASSERT_EQ(built.blas.colors.size(), 2u);
    ASSERT_EQ(cached.blas.colors.size(), 2u);
    for (size_t s = 0; s < 2; ++s)
        for (int k = 0; k < 9; ++k)
            EXPECT_EQ(cached.blas.colors[s].rgb[k], built.blas.colors[s].rgb[k]);
    // Each corner has its vertex's colour, wherever the triangulation and the tree put it.
    auto colorAt = [](vec3 p) {
        return p == vec3(0, 0, 0)   ? vec3(1, 0, 0)
               : p == vec3(1, 0, 0) ? vec3(0, 1, 0)
               : p == vec3(1, 1, 0) ? vec3(0, 0, 1)
                                    : vec3(1, 1, 1);
    };
    for (size_t s = 0; s < 2; ++s) {
        const Triangle& t = cached.blas.triangles[s];
        EXPECT_EQ(cached.blas.colors[s].Corner(0), colorAt(t.v0)) << s;
        EXPECT_EQ(cached.blas.colors[s].Corner(1), colorAt(t.v1)) << s;
        EXPECT_EQ(cached.blas.colors[s].Corner(2), colorAt(t.v2)) << s;
    }
}

}  // namespace
}  // namespace rtrt
