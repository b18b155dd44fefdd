// Vertex colours in mesh files: PLY's red/green/blue (or diffuse_*) of any type, integers as
// fractions of their type's largest value, kept through polygon triangulation; OBJ's
// `v x y z r g b`, through vertices split by normals, white where a vertex gives none; values
// outside [0, 1] clamped with a warning. The BLAS cache keeps them: model_cache_test.cpp.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/error.h"
#include "game/assets/mesh_io.h"
#include "tests/assets/mesh_test_files.h"

namespace rtrt {
namespace {

using namespace mesh_test;  // NOLINT(build/namespaces): the shared test helpers

std::string ColouredPly(const std::string& type, const std::string& prefix,
                        const std::string& vertices) {
    return "ply\nformat ascii 1.0\nelement vertex 4\n"
           "property float x\nproperty float y\nproperty float z\n"
           "property " +
           type + " " + prefix + "red\nproperty " + type + " " + prefix + "green\nproperty " +
           type + " " + prefix +
           "blue\nproperty uchar alpha\n"
           "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           vertices + "4 0 1 2 3\n";
}

TEST_F(MeshIoTest, PlyColoursOfEachTypeAreFractions) {
    const TriangleMesh bytes = LoadMesh(Write("bytes.ply", ColouredPly("uchar", "",
                                                                       "0 0 0 255 0 51 9\n"
                                                                       "1 0 0 0 255 0 9\n"
                                                                       "1 1 0 0 0 255 9\n"
                                                                       "0 1 0 128 128 128 9\n")));
    ASSERT_EQ(bytes.indices.size(), 2u);  // the quad, triangulated
    ASSERT_EQ(bytes.colors.size(), 4u);
    EXPECT_EQ(bytes.colors[0], vec3(1.0f, 0.0f, float(51.0 / 255.0)));
    EXPECT_EQ(bytes.colors[2], vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(bytes.colors[3], vec3(float(128.0 / 255.0)));
    const TriangleMesh shorts = LoadMesh(Write("shorts.ply", ColouredPly("ushort", "diffuse_",
                                                                         "0 0 0 65535 0 1 1\n"
                                                                         "1 0 0 0 0 0 1\n"
                                                                         "1 1 0 0 0 0 1\n"
                                                                         "0 1 0 0 0 0 1\n")));
    ASSERT_EQ(shorts.colors.size(), 4u);
    EXPECT_EQ(shorts.colors[0], vec3(1.0f, 0.0f, float(1.0 / 65535.0)));
    const TriangleMesh none = LoadMesh(Write("none.ply", ColouredPly("uchar", "no_",
                                                                     "0 0 0 1 1 1 1\n"
                                                                     "1 0 0 1 1 1 1\n"
                                                                     "1 1 0 1 1 1 1\n"
                                                                     "0 1 0 1 1 1 1\n")));
    EXPECT_TRUE(none.colors.empty());
}

TEST_F(MeshIoTest, PlyFloatColoursOutsideTheUnitRangeAreClampedWithAWarning) {
    const std::string path = Write("floats.ply", ColouredPly("float", "",
                                                             "0 0 0 1.5 0.25 -2 1\n"
                                                             "1 0 0 0.5 0.5 0.5 1\n"
                                                             "1 1 0 0 1 0 1\n"
                                                             "0 1 0 0 0 1 1\n"));
    ::testing::internal::CaptureStderr();
    const TriangleMesh mesh = LoadMesh(path);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("2 vertex colour components outside [0, 1] are clamped"),
              std::string::npos)
        << warnings;
    ASSERT_EQ(mesh.colors.size(), 4u);
    EXPECT_EQ(mesh.colors[0], vec3(1.0f, 0.25f, 0.0f));
    EXPECT_EQ(mesh.colors[1], vec3(0.5f));
    ExpectInputError(Write("nan.ply", ColouredPly("float", "",
                                                  "0 0 0 nan 0 0 1\n"
                                                  "1 0 0 0 0 0 1\n"
                                                  "1 1 0 0 0 0 1\n"
                                                  "0 1 0 0 0 0 1\n")),
                     "vertex 0", "colour is NaN or infinite");
}

TEST_F(MeshIoTest, ObjColoursFollowTheirVertices) {
    // Without normals: the vertices as they are. A fourth coordinate alone (w) is no colour.
    const TriangleMesh plain = LoadMesh(Write("plain.obj",
                                              "v 0 0 0 1 0 0\n"
                                              "v 1 0 0 0 1 0\n"
                                              "v 1 1 0 0 0 1\n"
                                              "f 1 2 3\n"));
    ASSERT_EQ(plain.colors.size(), 3u);
    EXPECT_EQ(plain.colors[1], vec3(0, 1, 0));
    EXPECT_TRUE(
        LoadMesh(Write("w.obj", "v 0 0 0 1\nv 1 0 0 1\nv 1 1 0 1\nf 1 2 3\n")).colors.empty());
    // With normals, vertices are split by them: each copy keeps its vertex's colour.
    const TriangleMesh split = LoadMesh(Write("split.obj",
                                              "v 0 0 0 0.25 0.5 0.75\n"
                                              "v 1 0 0 1 1 1\n"
                                              "v 1 1 0 0 0 0\n"
                                              "v 0 1 0 0.5 0.5 0.5\n"
                                              "vn 0 0 1\nvn 0 0.6 0.8\n"
                                              "f 1//1 2//1 3//1\nf 1//2 3//2 4//2\n"));
    ASSERT_EQ(split.positions.size(), 6u);
    ASSERT_EQ(split.colors.size(), 6u);
    for (size_t v = 0; v < split.positions.size(); ++v) {
        const vec3 p = split.positions[v];
        const vec3 want = p == vec3(0, 0, 0)   ? vec3(0.25f, 0.5f, 0.75f)
                          : p == vec3(1, 0, 0) ? vec3(1.0f)
                          : p == vec3(1, 1, 0) ? vec3(0.0f)
                                               : vec3(0.5f);
        EXPECT_EQ(split.colors[v], want) << "vertex " << v;
    }
}

TEST_F(MeshIoTest, ObjVerticesWithoutAColourAmongColouredOnesAreWhite) {
    const std::string path = Write("mixed.obj",
                                   "v 0 0 0\n"
                                   "v 1 0 0 0 1 0\n"
                                   "v 1 1 0\n"
                                   "f 1 2 3\n");
    ::testing::internal::CaptureStderr();
    const TriangleMesh mesh = LoadMesh(path);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("2 vertices without a colour (x y z r g b) among coloured ones are "
                            "white"),
              std::string::npos)
        << warnings;
    ASSERT_EQ(mesh.colors.size(), 3u);
    EXPECT_EQ(mesh.colors[0], vec3(1.0f));
    EXPECT_EQ(mesh.colors[1], vec3(0, 1, 0));
    EXPECT_EQ(mesh.colors[2], vec3(1.0f));
}

// Values past x y z that are not three numbers (words, RGBA) were ignored before colours were
// read, and still are, with a warning; numbers beyond float's range are clamped like any value
// above 1, once per component however many copies the normals split the vertex into.
TEST_F(MeshIoTest, ObjValuesPastXyzThatAreNoColourAreIgnoredWithAWarning) {
    ::testing::internal::CaptureStderr();
    const TriangleMesh odd = LoadMesh(Write("odd.obj",
                                            "v 0 0 0 a b c\n"
                                            "v 1 0 0 1 0 0 1\n"
                                            "v 1 1 0 0 1\n"
                                            "f 1 2 3\n"));
    std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_TRUE(odd.colors.empty());
    EXPECT_NE(warnings.find("3 vertex statements have values after x y z that are not a colour"),
              std::string::npos)
        << warnings;
    ::testing::internal::CaptureStderr();
    const TriangleMesh big =
        LoadMesh(Write("big.obj",
                       "v 0 0 0 1e39 0.5 -1e300\n"
                       "v 1 0 0 0 0 0\n"
                       "v 1 1 0 0 0 0\n"
                       "vn 0 0 1\nvn 0 1 0\nvn 1 0 0\n"
                       "f 1//1 2//1 3//1\nf 1//2 3//2 2//2\nf 1//3 2//3 3//3\n"));
    warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find(": 2 vertex colour components outside [0, 1] are clamped"),
              std::string::npos)
        << warnings;
    ASSERT_EQ(big.positions.size(), 9u);  // each vertex split in three by its normals
    for (size_t v = 0; v < big.positions.size(); ++v)
        if (big.positions[v] == vec3(0.0f)) EXPECT_EQ(big.colors[v], vec3(1.0f, 0.5f, 0.0f));
}

TEST_F(MeshIoTest, PlyDoubleColoursBeyondFloatsRangeAreClamped) {
    std::string ply = ColouredPly("double", "",
                                  "0 0 0 1e300 0.5 -1e300 1\n"
                                  "1 0 0 0 0 0 1\n"
                                  "1 1 0 0 0 0 1\n"
                                  "0 1 0 0 0 0 1\n");
    ::testing::internal::CaptureStderr();
    const TriangleMesh mesh = LoadMesh(Write("huge.ply", ply));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("2 vertex colour components outside [0, 1] are clamped"),
              std::string::npos)
        << warnings;
    ASSERT_EQ(mesh.colors.size(), 4u);
    EXPECT_EQ(mesh.colors[0], vec3(1.0f, 0.5f, 0.0f));
}

// Colours per face (as some exporters write them) are not read: a warning says so.
TEST_F(MeshIoTest, PlyFaceColoursAreNamedAsNotRead) {
    const std::string path = Write("faces.ply",
                                   "ply\nformat ascii 1.0\nelement vertex 3\n"
                                   "property float x\nproperty float y\nproperty float z\n"
                                   "element face 1\nproperty list uchar int vertex_indices\n"
                                   "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                                   "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n");
    ::testing::internal::CaptureStderr();
    const TriangleMesh mesh = LoadMesh(path);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(mesh.indices.size(), 1u);
    EXPECT_TRUE(mesh.colors.empty());
    EXPECT_NE(warnings.find("the faces' colours are not read"), std::string::npos) << warnings;
}

}  // namespace
}  // namespace rtrt
