#include "game/assets/mesh_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/error.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

// Real models come from tools/fetch_models.sh (tests/test_util.h finds them).
fs::path ModelDir() { return test::ModelDir(); }

uint32_t Crc32(std::string_view data) {
    uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char c : data) {
        crc ^= c;
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void AppendLittleEndian(std::string& out, uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) out += static_cast<char>((value >> (8 * i)) & 0xFF);
}

// A gzip member (RFC 1952) holding DATA in stored deflate blocks (RFC 1951): a valid file for
// gzread without linking zlib into the test.
std::string Gzip(std::string_view data) {
    std::string out = {'\x1f', '\x8b', 8, 0, 0, 0, 0, 0, 0, 3};
    size_t offset = 0;
    do {
        size_t length = std::min<size_t>(data.size() - offset, 0xFFFF);
        out += static_cast<char>(offset + length == data.size() ? 1 : 0);  // BFINAL, BTYPE 00
        AppendLittleEndian(out, length, 2);
        AppendLittleEndian(out, ~length & 0xFFFF, 2);
        out.append(data.substr(offset, length));
        offset += length;
    } while (offset < data.size());
    AppendLittleEndian(out, Crc32(data), 4);
    AppendLittleEndian(out, data.size() & 0xFFFFFFFFu, 4);
    return out;
}

// Binary PLY data in either byte order.
class Bytes {
  public:
    explicit Bytes(bool bigEndian) : bigEndian_(bigEndian) {}
    template <class T>
    Bytes& Put(T value) {
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        for (size_t i = 0; i < sizeof(T); ++i) {
            data_ += raw[bigEndian_ ? sizeof(T) - 1 - i : i];
        }
        return *this;
    }
    const std::string& Data() const { return data_; }

  private:
    bool bigEndian_;
    std::string data_;
};

class MeshIoTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("rtrt_mesh_io_" + std::to_string(getpid()) + "_" + info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string Write(const std::string& name, std::string_view contents) {
        std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary)
            .write(contents.data(), static_cast<std::streamsize>(contents.size()));
        return path;
    }

    fs::path dir_;
};

// LoadMesh(path) must throw an InputError naming the file, the field and the reason.
void ExpectInputError(const std::string& path, const std::string& field,
                      const std::string& reason) {
    try {
        LoadMesh(path);
        ADD_FAILURE() << "no InputError for " << path << ", expected " << field << ": " << reason;
    } catch (const InputError& error) {
        std::string what = error.what();
        EXPECT_EQ(error.File(), path);
        EXPECT_EQ(error.Field(), field) << what;
        EXPECT_NE(what.find(path), std::string::npos) << what;
        EXPECT_NE(error.Reason().find(reason), std::string::npos) << what;
    }
}

void ExpectUnitNormals(const TriangleMesh& mesh) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (vec3 n : mesh.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

void ExpectIndicesInRange(const TriangleMesh& mesh) {
    for (glm::uvec3 t : mesh.indices) {
        EXPECT_LT(t.x, mesh.positions.size());
        EXPECT_LT(t.y, mesh.positions.size());
        EXPECT_LT(t.z, mesh.positions.size());
    }
}

// ---------------------------------------------------------------------------------------------
// OBJ

TEST_F(MeshIoTest, ObjFanTriangulatesPolygons) {
    std::string path = Write("quad.obj",
                             "v 0 0 0\n"
                             "v 1 0 0\n"
                             "v 1 1 0\n"
                             "v 0.5 2 0\n"
                             "v 0 1 0\n"
                             "f 1 2 3 4 5\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.positions.size(), 5u);
    EXPECT_EQ(mesh.positions[3], vec3(0.5f, 2.0f, 0.0f));
    ASSERT_EQ(mesh.indices.size(), 3u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(mesh.indices[1], glm::uvec3(0, 2, 3));
    EXPECT_EQ(mesh.indices[2], glm::uvec3(0, 3, 4));
    ExpectUnitNormals(mesh);
    for (vec3 n : mesh.normals) EXPECT_EQ(n, vec3(0.0f, 0.0f, 1.0f));
}

TEST_F(MeshIoTest, ObjAcceptsCornerFormsNegativeIndicesAndIgnoredStatements) {
    std::string path = Write("forms.obj",
                             "# a comment\r\n"
                             "mtllib scene.mtl\r\n"
                             "o thing\r\n"
                             "g group\r\n"
                             "s 1\r\n"
                             "usemtl red\r\n"
                             "\r\n"
                             "v 0 0 0\r\n"
                             "v 2 0 0\r\n"
                             "v 0 2 0   # trailing comment\r\n"
                             "v 0 0 2\r\n"
                             "vt 0 0\r\n"
                             "vt 1 0\r\n"
                             "vt 0 1\r\n"
                             "f 1/1 2/2 3/3\r\n"
                             "f -4/-3 -2/-1 -3/-2\r\n"
                             "f 1 4 2\r\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.positions.size(), 4u);
    EXPECT_EQ(mesh.positions[3], vec3(0.0f, 0.0f, 2.0f));
    ASSERT_EQ(mesh.indices.size(), 3u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(mesh.indices[1], glm::uvec3(0, 2, 1));
    EXPECT_EQ(mesh.indices[2], glm::uvec3(0, 3, 1));
    ExpectUnitNormals(mesh);
}

TEST_F(MeshIoTest, ObjUsesFileNormalsAndSplitsVerticesPerNormal) {
    // Two faces of a box edge share vertices 1 and 2 but give them different normals.
    std::string path = Write("edge.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                             "vn 0 0 -2\nvn 0 -1 0\nvt 0 0\n"
                             "f 1//1 3//1 2//1\n"
                             "f 1/1/2 2/1/2 4/1/2\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.indices.size(), 2u);
    ASSERT_EQ(mesh.positions.size(), 6u);  // (v, vn) pairs: 1-1 3-1 2-1 1-2 2-2 4-2
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(mesh.indices[1], glm::uvec3(3, 4, 5));
    EXPECT_EQ(mesh.positions[1], vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(mesh.positions[5], vec3(0.0f, 0.0f, 1.0f));
    for (int v = 0; v < 3; ++v) EXPECT_EQ(mesh.normals[v], vec3(0.0f, 0.0f, -1.0f));
    for (int v = 3; v < 6; ++v) EXPECT_EQ(mesh.normals[v], vec3(0.0f, -1.0f, 0.0f));
}

TEST_F(MeshIoTest, ObjWithoutNormalsOnEveryCornerGetsAreaWeightedNormals) {
    // A triangle of area 2 facing +z and one of area 1 facing +x share vertices 1 and 2.
    std::string path = Write("weighted.obj",
                             "v 0 0 0\nv 0 2 0\nv -2 0 0\nv 0 0 1\nvn 1 0 0\n"
                             "f 1 2 3\n"
                             "f 1//1 2//1 4//1\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.positions.size(), 4u);
    ExpectUnitNormals(mesh);
    vec3 expected = glm::normalize(vec3(1.0f, 0.0f, 2.0f));
    EXPECT_NEAR(glm::distance(mesh.normals[0], expected), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(mesh.normals[1], expected), 0.0f, 1e-6f);
    EXPECT_EQ(mesh.normals[2], vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(mesh.normals[3], vec3(1.0f, 0.0f, 0.0f));
}

TEST_F(MeshIoTest, ObjDropsDegenerateFacesSilently) {
    std::string path = Write("degenerate.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "f 1 1 2\n"
                             "f 1 2\n"
                             "f 1 2 3 3\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.indices.size(), 1u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
}

TEST_F(MeshIoTest, ObjErrors) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    ExpectInputError(Write("range.obj", vertices + "f 1 2 4\n"), "line 4", "out of range");
    ExpectInputError(Write("zero.obj", vertices + "f 0 1 2\n"), "line 4", "out of range");
    ExpectInputError(Write("negative.obj", vertices + "f -4 1 2\n"), "line 4", "out of range");
    ExpectInputError(Write("normal.obj", vertices + "f 1//1 2//1 3//1\n"), "line 4",
                     "normal index 1 out of range");
    ExpectInputError(Write("texture.obj", vertices + "f 1/2 2/2 3/2\n"), "line 4",
                     "texture index 2 out of range");
    ExpectInputError(Write("corner.obj", vertices + "f 1/1/1/1 2 3\n"), "line 4",
                     "bad face corner");
    ExpectInputError(Write("word.obj", vertices + "f 1 two 3\n"), "line 4", "bad vertex index");
    ExpectInputError(Write("nan.obj", "v 0 0 0\nv nan 0 0\n"), "line 2", "NaN or infinite");
    ExpectInputError(Write("inf.obj", "v 0 0 0\nv 1e39 0 0\n"), "line 2", "NaN or infinite");
    ExpectInputError(Write("short.obj", "v 0 0\n"), "line 1", "needs three coordinates");
    ExpectInputError(Write("text.obj", "v 0 zero 0\n"), "line 1", "expected a number");
    ExpectInputError(Write("ply.obj", "ply\nformat ascii 1.0\n"), "line 1",
                     "unknown statement 'ply'");
    ExpectInputError(Write("empty.obj", vertices), "", "contains no triangles");
    ExpectInputError(Write("flat.obj", vertices + "f 1 2 2\n"), "", "contains no triangles");
}

// ---------------------------------------------------------------------------------------------
// PLY

const char* const kAsciiPly =
    "ply\n"
    "format ascii 1.0\n"
    "comment written by hand\n"
    "element vertex 5\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "property uchar red\n"
    "property list uchar float extra\n"
    "element edge 1\n"
    "property int vertex1\n"
    "property int vertex2\n"
    "element face 3\n"
    "property uchar flags\n"
    "property list uchar int vertex_indices\n"
    "property float quality\n"
    "end_header\n"
    "0 0 0 255 0\n"
    "1 0 0 255 2 0.5 0.5\n"
    "1 1 0 255 0\n"
    "0 1 0 255 1 7\n"
    "0.25 -0.5 +1.5e1 0 0\n"
    "0 1\n"
    "1 4 0 1 2 3 0.5\n"
    "0 3 0 0 1 1\n"
    "2 3 4 1 0 1\n";

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

// Four vertices (double x y z between skipped properties of every type), faces first.
std::string BinaryPly(bool bigEndian) {
    std::string header = std::string("ply\nformat ") +
                         (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                         " 1.0\n"
                         "element face 2\n"
                         "property list int short vertex_indices\n"
                         "property list uint double weights\n"
                         "element vertex 4\n"
                         "property char a\nproperty uchar b\nproperty short c\n"
                         "property ushort d\nproperty int e\n"
                         "property double x\nproperty double y\nproperty double z\n"
                         "property uint f\nproperty float g\n"
                         "end_header\n";
    Bytes data(bigEndian);
    data.Put<int32_t>(4).Put<int16_t>(0).Put<int16_t>(1).Put<int16_t>(2).Put<int16_t>(3);
    data.Put<uint32_t>(1).Put<double>(1.0);
    data.Put<int32_t>(3).Put<int16_t>(3).Put<int16_t>(3).Put<int16_t>(0);  // degenerate
    data.Put<uint32_t>(0);
    const double xyz[4][3] = {{0, 0, 0}, {1.5, 0, 0}, {1.5, 0.1, -2}, {0, 0.1, -2}};
    for (const auto& p : xyz) {
        data.Put<int8_t>(-1).Put<uint8_t>(2).Put<int16_t>(-3).Put<uint16_t>(4).Put<int32_t>(-5);
        data.Put<double>(p[0]).Put<double>(p[1]).Put<double>(p[2]);
        data.Put<uint32_t>(6).Put<float>(7.0f);
    }
    return header + data.Data();
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
                     "truncated");
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
