#include "game/assets/teapot.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

// Real models come from tools/fetch_models.sh (tests/test_util.h finds them).
fs::path ModelDir() { return test::ModelDir(); }

// Tests on POV-Ray's teapot.inc; skipped when tools/fetch_models.sh has not fetched it.
class TeapotTest : public ::testing::Test {
  protected:
    void SetUp() override {
        path_ = (ModelDir() / "teapot.inc").string();
        if (ModelDir().empty() || !fs::exists(path_)) {
            GTEST_SKIP() << "teapot.inc is not in '" << ModelDir().string()
                         << "': run tools/fetch_models.sh";
        }
    }

    std::string path_;
};

TEST_F(TeapotTest, ResolutionSixGives2256Triangles) {
    // 32 patches * 36 quads * 2 triangles, less one triangle per quad along the collapsed edges
    // of the four lid-top and four bottom patches.
    EXPECT_EQ(TessellateTeapot(path_, 6).indices.size(), 2256u);
}

TEST_F(TeapotTest, TriangleCountFollowsResolution) {
    for (int r : {1, 2, 3, 5, 8}) {
        EXPECT_EQ(TessellateTeapot(path_, r).indices.size(),
                  static_cast<size_t>(64 * r * r - 8 * r))
            << "resolution " << r;
    }
}

TEST_F(TeapotTest, StandsOnYZeroWithSpoutTowardsPlusX) {
    TriangleMesh mesh = TessellateTeapot(path_, 6);
    Aabb bounds = mesh.Bounds();
    EXPECT_EQ(bounds.min.y, 0.0f);
    EXPECT_EQ(bounds.max.y, 3.15f);
    EXPECT_EQ(bounds.min.x, -3.0f);  // the handle
    EXPECT_NEAR(bounds.max.x, 3.43f, 0.01f);
    EXPECT_EQ(bounds.min.z, -2.0f);
    EXPECT_EQ(bounds.max.z, 2.0f);
}

TEST_F(TeapotTest, WeldedMeshWithOutwardUnitNormals) {
    // An odd resolution: plain de Casteljau from one end leaves seams unwelded there.
    TriangleMesh mesh = TessellateTeapot(path_, 7);
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_NEAR(glm::length(mesh.normals[i]), 1.0f, 1e-5f);
        for (size_t j = i + 1; j < mesh.positions.size(); ++j) {
            ASSERT_GT(glm::distance(mesh.positions[i], mesh.positions[j]), 1e-4f)
                << "vertices " << i << " and " << j << " were not welded";
        }
    }
    for (glm::uvec3 t : mesh.indices) {
        ASSERT_LT(std::max({t.x, t.y, t.z}), mesh.positions.size());
        EXPECT_TRUE(t.x != t.y && t.y != t.z && t.x != t.z);
    }
    size_t top = 0, bottom = 0, side = 0;
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        if (mesh.positions[i].y > mesh.positions[top].y) top = i;
        if (mesh.positions[i] == vec3(0.0f)) bottom = i;
        if (mesh.positions[i].z > mesh.positions[side].z) side = i;
    }
    EXPECT_EQ(mesh.positions[bottom], vec3(0.0f));
    EXPECT_GT(mesh.normals[top].y, 0.999f);      // the lid knob
    EXPECT_LT(mesh.normals[bottom].y, -0.999f);  // the centre of the base
    EXPECT_GT(mesh.normals[side].z, 0.99f);      // the widest point of the body
}

class TeapotFileTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("rtrt_teapot_" + std::to_string(getpid()) + "_" + info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string Write(const std::string& contents) {
        std::string path = (dir_ / "teapot.inc").string();
        std::ofstream(path, std::ios::binary) << contents;
        return path;
    }

    fs::path dir_;
};

// Patch K is the flat square [10K, 10K + 3] x [0, 3] in POV-Ray's z-up frame.
std::string FlatPatch(int k, int points = 16) {
    std::string text = "   bicubic_patch { type 1 flatness 0.01 u_steps 3 v_steps 3\n";
    for (int i = 0; i < points; ++i) {
        int row = i / 4, column = i % 4;
        text += " <" + std::to_string(10 * k + column) + ", " + std::to_string(row) + ", 0>";
    }
    return text + "\n      texture { pigment { color rgb <1, 0, 0> } }\n   }\n";
}

std::string FlatPatches(int count) {
    std::string text = "// bicubic_patch { in a comment }\n#declare Name = \"bicubic_patch\";\n";
    text += "union {\n";
    for (int k = 0; k < count; ++k) text += FlatPatch(k);
    return text + "   rotate <-90, 0, 0>\n}\n";
}

TEST_F(TeapotFileTest, TessellatesEachPatchAndTurnsZUpIntoYUp) {
    TriangleMesh mesh = TessellateTeapot(Write(FlatPatches(32)), 3);
    EXPECT_EQ(mesh.positions.size(), 32u * 16u);
    EXPECT_EQ(mesh.indices.size(), 32u * 18u);
    // File point (x, y, z) lands at (x, z, -y); grid corners are the control points exactly.
    EXPECT_EQ(mesh.positions[0], vec3(0.0f, 0.0f, 0.0f));
    EXPECT_EQ(mesh.positions[3], vec3(3.0f, 0.0f, 0.0f));
    EXPECT_EQ(mesh.positions[15], vec3(3.0f, 0.0f, -3.0f));
    EXPECT_EQ(mesh.positions[16], vec3(10.0f, 0.0f, 0.0f));
    EXPECT_EQ(mesh.positions[1], vec3(1.0f, 0.0f, 0.0f));
    for (vec3 n : mesh.normals) EXPECT_NEAR(glm::distance(n, vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-6f);
}

TEST_F(TeapotFileTest, UvVectorsAreNotControlPoints) {
    std::string text = FlatPatches(32);
    size_t at = text.find("u_steps 3");
    text.insert(at, "uv_vectors <0, 0> <1, 0> <1, 1> <0, 1> ");
    EXPECT_EQ(TessellateTeapot(Write(text), 2).indices.size(), 32u * 8u);
}

// TessellateTeapot(path_, resolution) must throw an InputError naming the file, field and reason.
void ExpectTeapotError(const std::string& path, int resolution, const std::string& field,
                       const std::string& reason) {
    try {
        TessellateTeapot(path, resolution);
        ADD_FAILURE() << "no InputError, expected " << field << ": " << reason;
    } catch (const InputError& error) {
        std::string what = error.what();
        EXPECT_EQ(error.File(), path);
        EXPECT_NE(what.find(path), std::string::npos) << what;
        EXPECT_EQ(error.Field(), field) << what;
        EXPECT_NE(error.Reason().find(reason), std::string::npos) << what;
    }
}

TEST_F(TeapotFileTest, Errors) {
    ExpectTeapotError((dir_ / "missing.inc").string(), 6, "", "cannot open file");
    ExpectTeapotError(Write(FlatPatches(31)), 6, "", "expected 32 bicubic_patch blocks, found 31");
    ExpectTeapotError(Write(FlatPatches(33)), 6, "", "expected 32 bicubic_patch blocks, found 33");
    ExpectTeapotError(Write(""), 6, "", "found 0");

    std::string text = FlatPatches(32);
    std::string fewer = text;
    fewer.replace(fewer.find(FlatPatch(2)), FlatPatch(2).size(), FlatPatch(2, 15));
    ExpectTeapotError(Write(fewer), 6, "patch 3", "expected 16 control points, found 15");

    std::string flat = text;
    flat.replace(flat.find("<11, 0, 0>"), 10, "<11, 0>");
    ExpectTeapotError(Write(flat), 6, "patch 2", "control point 2 is not <x, y, z>");
    std::string word = text;
    word.replace(word.find("<11, 0, 0>"), 10, "<11, zero, 0>");
    ExpectTeapotError(Write(word), 6, "patch 2", "control point 2");
    std::string nan = text;
    nan.replace(nan.find("<11, 0, 0>"), 10, "<11, nan, 0>");
    ExpectTeapotError(Write(nan), 6, "patch 2", "finite");

    std::string open = text.substr(0, text.rfind("texture"));
    ExpectTeapotError(Write(open), 6, "patch 32", "unterminated");
    std::string brace = text;
    brace.replace(brace.find("bicubic_patch {", brace.find("union")), 15, "bicubic_patch <");
    ExpectTeapotError(Write(brace), 6, "patch 1", "expected '{'");

    // A block inside a block is not a patch of its own: the search goes on after the outer
    // block (searching inside each block again made deep nesting take quadratic time).
    std::string points;
    for (int i = 0; i < 16; ++i)
        points += " <" + std::to_string(i % 4) + ", " + std::to_string(i / 4) + ", 0>";
    std::string nested;
    for (int k = 0; k < 32; ++k) nested = "bicubic_patch { " + nested + points + " }\n";
    ExpectTeapotError(Write(nested), 6, "", "expected 32 bicubic_patch blocks, found 1");

    ExpectTeapotError(Write(text), 0, "resolution", "must be in [1, 256]");
    ExpectTeapotError(Write(text), 100000, "resolution", "got 100000");
}

}  // namespace
}  // namespace rtrt
