// LoadMesh (mesh_io.h): what every format shares: file errors, hostile bytes, the real models.
#include "game/assets/mesh_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "tests/assets/mesh_test_files.h"

namespace rtrt {
namespace {

using namespace mesh_test;  // NOLINT(build/namespaces): the shared test helpers
namespace fs = std::filesystem;

TEST_F(MeshIoTest, FileErrors) {
    std::string missing = (dir_ / "missing.ply").string();
    ExpectInputError(missing, "", "cannot open file: No such file or directory");
    ExpectInputError((dir_ / "missing.obj").string(), "", "cannot open file");
    ExpectInputError(Write("mesh.stl", "solid\n"), "", "unknown mesh file extension");
    ExpectInputError(Write("mesh.ply.bz2", "BZh"), "", "unknown mesh file extension");
    fs::create_directories(dir_ / "folder.obj");
    ExpectInputError((dir_ / "folder.obj").string(), "", "not a regular file");
    ExpectInputError(Write("plain.ply.gz", kAsciiPly), "", "not a gzip file");
    std::string packed = Gzip(kAsciiPly);
    ExpectInputError(Write("cut.ply.gz", packed.substr(0, packed.size() / 2)), "",
                     "corrupt gzip data");
    try {
        LoadMesh(Write("cut.ply.gz", packed.substr(0, packed.size() / 2)));
    } catch (const InputError& error) {
        // zlib's message starts with the path, which the error names once already.
        EXPECT_EQ(error.Reason().find(error.File()), std::string::npos) << error.what();
    }
    std::string corrupt = packed;
    corrupt[corrupt.size() - 6] ^= 0x55;  // the CRC-32
    ExpectInputError(Write("crc.ply.gz", corrupt), "", "corrupt gzip data");
    ExpectInputError(Write("empty.ply", ""), "header", "bad magic");
}

// Mutated and truncated copies of valid files must load or throw InputError, never crash.
TEST_F(MeshIoTest, HostileInputNeverCrashes) {
    const std::string obj =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvt 0 0\n"
        "f 1/1/1 2/1/1 3/1/1\nf -4 -3 -1\n";
    const std::pair<std::string, std::string> bases[] = {
        {"fuzz.obj", obj},
        {"fuzz.ply", kAsciiPly},
        {"fuzz_le.ply", BinaryPly(false)},
        {"fuzz_be.ply", BinaryPly(true)},
    };
    const char kInteresting[] = {'\0', '\xff', '\x80', ' ', '\n', '-', '9', '/', 'e', 'n'};
    std::mt19937 random(12345);
    int loaded = 0, rejected = 0;
    for (const auto& [name, base] : bases) {
        for (int trial = 0; trial < 300; ++trial) {
            std::string data = base;
            int edits = 1 + static_cast<int>(random() % 4);
            for (int e = 0; e < edits; ++e) {
                size_t at = random() % data.size();
                data[at] = random() % 2 ? kInteresting[random() % sizeof(kInteresting)]
                                        : static_cast<char>(random());
            }
            if (trial % 5 == 0) data.resize(random() % data.size());
            std::string path = Write(name, data);
            try {
                TriangleMesh mesh = LoadMesh(path);
                ExpectIndicesInRange(mesh);
                ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
                ++loaded;
            } catch (const InputError& error) {
                EXPECT_EQ(error.File(), path);
                ++rejected;
            }
        }
    }
    EXPECT_GT(loaded, 0);
    EXPECT_GT(rejected, 0);
}

// ---------------------------------------------------------------------------------------------
// The Stanford dragon (tools/fetch_models.sh)

// A model that tools/fetch_models.sh fetched, or an empty path when it is not there.
std::string FetchedModel(const std::string& name) {
    fs::path dir = ModelDir();
    if (dir.empty() || !fs::exists(dir / name)) return {};
    return (dir / name).string();
}

TEST(MeshIoModelTest, DragonRes4) {
    std::string path = FetchedModel("dragon_vrip_res4.ply.gz");
    if (path.empty()) {
        GTEST_SKIP() << "dragon_vrip_res4.ply.gz is not in '" << ModelDir().string()
                     << "': run tools/fetch_models.sh";
    }
    TriangleMesh mesh = LoadMesh(path);
    EXPECT_EQ(mesh.indices.size(), 11102u);
    EXPECT_EQ(mesh.positions.size(), 5205u);
    EXPECT_EQ(mesh.positions[0], vec3(0.0317083f, 0.0557939f, -0.049836f));
    ExpectUnitNormals(mesh);
    ExpectIndicesInRange(mesh);
}

TEST(MeshIoModelTest, DragonFull) {
    std::string path = FetchedModel("dragon_vrip.ply.gz");
    if (path.empty()) {
        GTEST_SKIP() << "dragon_vrip.ply.gz is not in '" << ModelDir().string()
                     << "': run tools/fetch_models.sh";
    }
    TriangleMesh mesh = LoadMesh(path);
    EXPECT_EQ(mesh.indices.size(), 871414u);
    EXPECT_EQ(mesh.positions.size(), 437645u);
    EXPECT_EQ(mesh.positions[0], vec3(0.032027f, 0.056575f, -0.0503644f));
    ExpectIndicesInRange(mesh);
    ExpectUnitNormals(mesh);
}

}  // namespace
}  // namespace rtrt
