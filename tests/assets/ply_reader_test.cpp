// Stanford PLY files loaded by LoadMesh (ply_reader.h): ASCII and binary, gzip, strips, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "game/assets/mesh_io.h"
#include "tests/assets/mesh_test_files.h"

namespace rtrt {
namespace {

using namespace mesh_test;  // NOLINT(build/namespaces): the shared test helpers

TEST_F(MeshIoTest, AsciiPlySkipsOtherPropertiesAndElements) {
    TriangleMesh mesh = LoadMesh(Write("mesh.ply", kAsciiPly));
    ASSERT_EQ(mesh.positions.size(), 5u);
    EXPECT_EQ(mesh.positions[1], vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(mesh.positions[4], vec3(0.25f, -0.5f, 15.0f));
    ASSERT_EQ(mesh.indices.size(), 3u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(mesh.indices[1], glm::uvec3(0, 2, 3));
    EXPECT_EQ(mesh.indices[2], glm::uvec3(4, 1, 0));
    ExpectUnitNormals(mesh);
    EXPECT_EQ(mesh.normals[2], vec3(0.0f, 0.0f, 1.0f));
}

TEST_F(MeshIoTest, GzippedAsciiPlyMatchesPlainOne) {
    TriangleMesh plain = LoadMesh(Write("mesh.ply", kAsciiPly));
    TriangleMesh packed = LoadMesh(Write("mesh.PLY.GZ", Gzip(kAsciiPly)));
    EXPECT_EQ(packed.positions, plain.positions);
    EXPECT_EQ(packed.indices, plain.indices);
    EXPECT_EQ(packed.normals, plain.normals);
}

TEST_F(MeshIoTest, AsciiPlyUsesFileNormalsAndVertexIndexName) {
    std::string path = Write("normals.ply",
                             "ply\r\n"
                             "format ascii 1.0\r\n"
                             "element vertex 3\r\n"
                             "property double x\r\nproperty double y\r\nproperty double z\r\n"
                             "property float nx\r\nproperty float ny\r\nproperty float nz\r\n"
                             "element face 1\r\n"
                             "property list ushort uint vertex_index\r\n"
                             "end_header\r\n"
                             "0 0 0 0 2 0\r\n"
                             "1 0 0 0 1 0\r\n"
                             "0 0 1 3 4 0\r\n"
                             "3 0 1 2\r\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.indices.size(), 1u);
    EXPECT_EQ(mesh.normals[0], vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(mesh.normals[1], vec3(0.0f, 1.0f, 0.0f));
    EXPECT_NEAR(glm::distance(mesh.normals[2], vec3(0.6f, 0.8f, 0.0f)), 0.0f, 1e-6f);
}

TEST_F(MeshIoTest, PlyNormalsWithoutDirectionFallBackPerVertex) {
    // Vertex 3's normal is zero: it takes the computed one (+z), the others keep the file's.
    std::string path = Write("zero_normal.ply",
                             "ply\nformat ascii 1.0\nelement vertex 4\n"
                             "property float x\nproperty float y\nproperty float z\n"
                             "property float nx\nproperty float ny\nproperty float nz\n"
                             "element face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n"
                             "0 0 0 0.6 0 0.8\n1 0 0 0.6 0 0.8\n1 1 0 0 0 0\n0 1 0 0 0 2\n"
                             "4 0 1 2 3\n");
    TriangleMesh mesh = LoadMesh(path);
    ExpectUnitNormals(mesh);
    EXPECT_NEAR(glm::distance(mesh.normals[0], vec3(0.6f, 0.0f, 0.8f)), 0.0f, 1e-6f);
    EXPECT_EQ(mesh.normals[2], vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(mesh.normals[3], vec3(0.0f, 0.0f, 1.0f));
}

// A polygon is buffered until the vertices are read, without the corners that repeat the one
// before (a face of 255 copies of a vertex cost 1 KB of buffer and made nothing).
TEST_F(MeshIoTest, PlyPolygonsOfRepeatedCornersMakeNothing) {
    std::string faces;
    for (int face = 0; face < 1000; ++face) {
        faces += "255";
        for (int corner = 0; corner < 255; ++corner) faces += " 0";
        faces += "\n";
    }
    const std::string header =
        "ply\nformat ascii 1.0\nelement face 1001\nproperty list uchar int vertex_indices\n"
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    const TriangleMesh mesh =
        LoadMesh(Write("repeated.ply", header + faces + "5 0 0 1 1 2\n0 0 0\n1 0 0\n0 1 0\n"));
    ASSERT_EQ(mesh.indices.size(), 1u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
}

TEST_F(MeshIoTest, PlyTriangleStripsKeepTheirWinding) {
    // A face, two strips of two triangles in one list (-1 ends the first), and the same joined
    // by repeated indices.
    std::string path = Write("strips.ply",
                             "ply\nformat ascii 1.0\nelement vertex 8\n"
                             "property float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\n"
                             "element tristrips 2\nproperty list int int vertex_indices\n"
                             "end_header\n"
                             "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n3 0 0\n3 1 0\n2 1 0\n"
                             "3 0 1 2\n"
                             "9 0 1 3 2 -1 4 5 7 6\n"
                             "10 0 1 3 2 2 4 4 5 7 6\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.indices.size(), 9u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(mesh.indices[1], glm::uvec3(0, 1, 3));
    EXPECT_EQ(mesh.indices[2], glm::uvec3(3, 1, 2));
    EXPECT_EQ(mesh.indices[3], glm::uvec3(4, 5, 7));
    EXPECT_EQ(mesh.indices[4], glm::uvec3(7, 5, 6));
    // The same strips joined by repeated indices: the four degenerate triangles dropped, the
    // alternation kept.
    for (size_t i = 0; i < 4; ++i) EXPECT_EQ(mesh.indices[5 + i], mesh.indices[1 + i]);
    for (glm::uvec3 t : mesh.indices) {
        const vec3 n = glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                  mesh.positions[t.z] - mesh.positions[t.x]);
        EXPECT_GT(n.z, 0.0f);
    }
    ExpectInputError(Write("strip_range.ply",
                           "ply\nformat ascii 1.0\nelement vertex 3\n"
                           "property float x\nproperty float y\nproperty float z\n"
                           "element tristrips 1\nproperty list int int vertex_indices\n"
                           "end_header\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2 -2\n"),
                     "tristrips 0", "vertex index -2 out of range");
}

TEST_F(MeshIoTest, BinaryPlyBothByteOrders) {
    for (bool bigEndian : {false, true}) {
        SCOPED_TRACE(bigEndian ? "big endian" : "little endian");
        std::string ply = BinaryPly(bigEndian);
        for (const std::string& path : {Write("mesh.ply", ply), Write("mesh.ply.gz", Gzip(ply))}) {
            TriangleMesh mesh = LoadMesh(path);
            ASSERT_EQ(mesh.positions.size(), 4u);
            EXPECT_EQ(mesh.positions[2], vec3(1.5f, 0.1f, -2.0f));
            ASSERT_EQ(mesh.indices.size(), 2u);
            EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
            EXPECT_EQ(mesh.indices[1], glm::uvec3(0, 2, 3));
            ExpectUnitNormals(mesh);
            EXPECT_NEAR(glm::distance(mesh.normals[3], glm::normalize(vec3(0, 2, 0.1f))), 0.0f,
                        1e-6f);
        }
    }
}

std::string PlyHeader(const std::string& format, int vertices, int faces,
                      const std::string& countType = "uchar") {
    return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
           std::to_string(faces) + "\nproperty list " + countType +
           " int vertex_indices\nend_header\n";
}

TEST_F(MeshIoTest, PlyHeaderErrors) {
    ExpectInputError(Write("magic.ply", "plx\nformat ascii 1.0\nend_header\n"), "header",
                     "bad magic");
    ExpectInputError(Write("obj.ply", "v 0 0 0\n"), "header", "bad magic");
    ExpectInputError(Write("format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"),
                     "header line 2", "unknown format");
    ExpectInputError(Write("version.ply", "ply\nformat ascii 2.0\nend_header\n"), "header line 2",
                     "format");
    ExpectInputError(Write("end.ply", "ply\nformat ascii 1.0\nelement vertex 0\n"), "header line 4",
                     "no end_header");
    ExpectInputError(Write("type.ply",
                           "ply\nformat ascii 1.0\nelement vertex 1\n"
                           "property float128 x\nend_header\n0\n"),
                     "header line 4", "known types");
    ExpectInputError(Write("orphan.ply", "ply\nformat ascii 1.0\nproperty float x\n"),
                     "header line 3", "property before element");
    ExpectInputError(Write("keyword.ply", "ply\nformat ascii 1.0\nelephant 3\nend_header\n"),
                     "header line 3", "unknown keyword");
    ExpectInputError(Write("noformat.ply", "ply\nend_header\n"), "header line 2",
                     "before the format line");
    ExpectInputError(Write("count.ply", "ply\nformat ascii 1.0\nelement vertex -3\n"),
                     "header line 3", "element <name> <count>");
    ExpectInputError(Write("nox.ply",
                           "ply\nformat ascii 1.0\nelement vertex 1\n"
                           "property float y\nproperty float z\nend_header\n0 0\n"),
                     "header", "no property 'x'");
    ExpectInputError(Write("noindices.ply",
                           "ply\nformat ascii 1.0\nelement vertex 1\n"
                           "property float x\nproperty float y\n"
                           "property float z\nelement face 1\n"
                           "property list uchar int corners\nend_header\n"
                           "0 0 0\n3 0 0 0\n"),
                     "header", "no vertex_indices list");
    ExpectInputError(Write("floatcount.ply",
                           "ply\nformat ascii 1.0\nelement face 1\n"
                           "property list float int vertex_indices\n"
                           "end_header\n3 0 0 0\n"),
                     "header line 4", "count type must be an integer");
    ExpectInputError(Write("novertex.ply", "ply\nformat ascii 1.0\nend_header\n"), "header",
                     "no vertex element");
    ExpectInputError(
        Write("twice.ply", PlyHeader("ascii", 0, 0)
                               .replace(std::string_view("ply\nformat ascii 1.0\n").size(), 0,
                                        "element vertex 0\nproperty float x\n")),
        "header", "more than one element 'vertex'");
    ExpectInputError(Write("empty_element.ply",
                           "ply\nformat ascii 1.0\nelement nothing 5\n"
                           "end_header\n"),
                     "header", "element 'nothing' has no properties");
}

TEST_F(MeshIoTest, PlyCountsBeyondTheFileSizeAreRejectedBeforeAllocating) {
    ExpectInputError(Write("huge.ply", PlyHeader("binary_little_endian", 2000000000, 1)), "header",
                     "more than the 0 bytes of data can hold");
    ExpectInputError(
        Write("huge_faces.ply", PlyHeader("ascii", 3, 1000000) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
        "header", "element 'face' declares 1000000 records");
    ExpectInputError(Write("overflow.ply",
                           "ply\nformat ascii 1.0\n"
                           "element vertex 99999999999999999999999\n"),
                     "header line 3", "element <name> <count>");
    Bytes list(false);
    list.Put<uint32_t>(0xFFFFFFFFu);
    ExpectInputError(Write("list.ply",
                           "ply\nformat binary_little_endian 1.0\n"
                           "element vertex 0\nproperty float x\nproperty float y\n"
                           "property float z\nproperty list uint uint junk\n"
                           "element face 1\nproperty list uint uint vertex_indices\n"
                           "end_header\n" +
                               list.Data()),
                     "face 0", "truncated");
}

TEST_F(MeshIoTest, PlyDataErrors) {
    const std::string ascii = PlyHeader("ascii", 3, 1);
    ExpectInputError(Write("nan.ply", ascii + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), "vertex 1",
                     "NaN or infinite");
    ExpectInputError(Write("inf.ply", ascii + "0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n"), "vertex 2",
                     "NaN or infinite");
    ExpectInputError(Write("word.ply", ascii + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"), "vertex 1",
                     "expected a number, found 'x'");
    ExpectInputError(Write("index.ply", ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"), "face 0",
                     "vertex index 3 out of range (3 vertices)");
    ExpectInputError(Write("negative.ply", ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), "face 0",
                     "vertex index -1 out of range");
    ExpectInputError(Write("fraction.ply", ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n"), "face 0",
                     "expected an integer");
    ExpectInputError(Write("truncated.ply", ascii + "0.000000000001 0.000000000002 0\n"
                                                    "1.000000000001 0.000000000002 0\n"),
                     "vertex 2", "truncated");
    ExpectInputError(Write("shortface.ply", ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"), "face 0",
                     "the line ends before the record does");
    ExpectInputError(Write("noface.ply",
                           "ply\nformat ascii 1.0\nelement vertex 1\n"
                           "property float x\nproperty float y\n"
                           "property float z\nend_header\n0 0 0\n"),
                     "", "contains no triangles");
    ExpectInputError(Write("degenerate.ply", ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n"), "",
                     "contains no triangles");

    const std::string binary = PlyHeader("binary_little_endian", 3, 1);
    Bytes vertices(false);
    for (float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f}) vertices.Put(v);
    vertices.Put(0.0f).Put(std::numeric_limits<float>::infinity()).Put(0.0f);
    ExpectInputError(Write("inf_binary.ply", binary + vertices.Data() + "\x03"), "vertex 2",
                     "NaN or infinite");
    Bytes good(false);
    for (float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) good.Put(v);
    Bytes face = good;
    face.Put<uint8_t>(3).Put<int32_t>(0).Put<int32_t>(1);
    ExpectInputError(Write("cut.ply", binary + face.Data() + std::string("\x02\x00", 2)), "face 0",
                     "truncated");
    Bytes big = good;
    big.Put<uint8_t>(3).Put<int32_t>(0).Put<int32_t>(1).Put<int32_t>(1 << 30);
    ExpectInputError(Write("big_index.ply", binary + big.Data()), "face 0",
                     "vertex index 1073741824 out of range");
    Bytes negative = good;
    negative.Put<int8_t>(-2);
    ExpectInputError(Write("negative_count.ply",
                           PlyHeader("binary_little_endian", 3, 1, "char") + negative.Data()),
                     "face 0", "negative vertex count");
}

// The data must be what the header announces: records one to a line in ASCII, no more and no
// fewer; the shifted, longer or mistyped files below had loaded as other meshes, or lost faces.
TEST_F(MeshIoTest, PlyDataMustFollowItsHeader) {
    const std::string ascii = PlyHeader("ascii", 3, 1);
    const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
    ExpectInputError(Write("shifted.ply", ascii + "0 0 0 7\n1 0\n0 1 0\n3 0 1 2\n"), "vertex 0",
                     "more values on the line than the header's properties ('7')");
    ExpectInputError(Write("extra_index.ply", ascii + vertices + "3 0 1 2 5\n"), "face 0",
                     "more values on the line than the header's properties ('5')");
    ExpectInputError(Write("trailing.ply", ascii + vertices + "3 0 1 2\ngarbage\n"), "",
                     "text after the last record the header announces ('garbage')");
    // A count is not held to its type's range (Blender writes n-gons of more than 255 corners
    // under a uchar count), but to the line.
    ExpectInputError(Write("wide_count.ply", ascii + vertices + "300 0 1 2\n"), "face 0",
                     "the line ends before the record does");
    std::string ngon =
        "ply\nformat ascii 1.0\nelement vertex 300\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    std::string corners = "300";
    for (int i = 0; i < 300; ++i) {
        const double a = 2.0 * 3.141592653589793 * i / 300;
        ngon += std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
        corners += " " + std::to_string(i);
    }
    EXPECT_EQ(LoadMesh(Write("ngon.ply", ngon + corners + "\n")).indices.size(), 298u);
    testing::internal::CaptureStderr();
    const TriangleMesh withEdge = LoadMesh(
        Write("two_corners.ply", PlyHeader("ascii", 3, 2) + vertices + "2 0 1\n3 0 1 2\n"));
    const std::string edgeWarning = testing::internal::GetCapturedStderr();
    EXPECT_EQ(withEdge.indices.size(), 1u);
    EXPECT_NE(edgeWarning.find("two_corners.ply: 1 faces of fewer than 3 corners"),
              std::string::npos)
        << edgeWarning;
    ExpectInputError(Write("duplicate_x.ply",
                           "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                           "property float x\nproperty float y\nproperty float z\nend_header\n"
                           "0 0 0 0\n1 1 0 0\n0 0 1 0\n"),
                     "header", "element vertex has the property 'x' twice");
    // Properties rtrt skips may repeat (real files have such duplicates); a repeated colour
    // channel leaves the colours unread, with a warning.
    ::testing::internal::CaptureStderr();
    const TriangleMesh repeated = LoadMesh(Write("duplicate_red.ply",
                                                 "ply\nformat ascii 1.0\nelement vertex 3\n"
                                                 "property float x\nproperty float y\n"
                                                 "property float z\nproperty uchar red\n"
                                                 "property uchar red\nproperty uchar green\n"
                                                 "property uchar blue\nelement face 1\n"
                                                 "property list uchar int vertex_indices\n"
                                                 "end_header\n0 0 0 1 2 3 4\n1 0 0 1 2 3 4\n"
                                                 "0 1 0 1 2 3 4\n3 0 1 2\n"));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(repeated.indices.size(), 1u);
    EXPECT_TRUE(repeated.colors.empty());
    EXPECT_NE(warnings.find("a vertex colour property (red green blue) is named twice"),
              std::string::npos)
        << warnings;
    // Whitespace after the last record, and blank lines between records, are fine, as are NUL
    // padding and a DOS end-of-file mark at the end.
    EXPECT_EQ(LoadMesh(Write("spaced.ply", ascii + vertices + "\n3 0 1 2  \n\n")).indices.size(),
              1u);
    EXPECT_EQ(LoadMesh(Write("padded.ply",
                             ascii + vertices + "3 0 1 2\n" + std::string(4, '\0') + "\x1a"))
                  .indices.size(),
              1u);

    Bytes data(false);
    for (float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) data.Put(v);
    data.Put<uint8_t>(3).Put<int32_t>(0).Put<int32_t>(1).Put<int32_t>(2);
    const std::string binary = PlyHeader("binary_little_endian", 3, 1);
    EXPECT_EQ(LoadMesh(Write("one_face.ply", binary + data.Data())).indices.size(), 1u);
    // Binary data cannot tell records the header does not announce from a writer's padding: the
    // bytes after the last record are a warning, and the announced records load.
    data.Put<uint8_t>(3).Put<int32_t>(2).Put<int32_t>(1).Put<int32_t>(0);
    testing::internal::CaptureStderr();
    const TriangleMesh longer = LoadMesh(Write("two_faces.ply", binary + data.Data()));
    const std::string warning = testing::internal::GetCapturedStderr();
    EXPECT_EQ(longer.indices.size(), 1u);
    EXPECT_NE(warning.find("two_faces.ply: 13 bytes after the last record the header announces are "
                           "ignored (do its counts match the data?)"),
              std::string::npos)
        << warning;
}

}  // namespace
}  // namespace rtrt
