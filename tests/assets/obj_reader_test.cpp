// Wavefront OBJ files loaded by LoadMesh (obj_reader.h), and polygons split in both formats.
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

// The sum of the triangles' areas; a concave polygon filled wrongly covers more than its own.
double Area(const TriangleMesh& mesh) {
    double area = 0.0;
    for (glm::uvec3 t : mesh.indices) {
        const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    return area;
}

// A U of 3 x 3 with a notch of 1 x 2 between its arms (area 7), one face of eight corners.
const char* const kUVertices = "0 0 0\n3 0 0\n3 3 0\n2 3 0\n2 1 0\n1 1 0\n1 3 0\n0 3 0\n";

TEST_F(MeshIoTest, ConcavePolygonsAreEarClippedInObjAndPly) {
    std::string obj;
    for (std::string_view rest = kUVertices; !rest.empty();) {
        obj += "v " + std::string(rest.substr(0, rest.find('\n') + 1));
        rest.remove_prefix(rest.find('\n') + 1);
    }
    const TriangleMesh fromObj = LoadMesh(Write("u.obj", obj + "f 1 2 3 4 5 6 7 8\n"));
    // The face first: its polygon waits for the vertices.
    const TriangleMesh fromPly =
        LoadMesh(Write("u.ply",
                       "ply\nformat ascii 1.0\nelement face 3\n"
                       "property list uchar int vertex_indices\nelement vertex 8\n"
                       "property float x\nproperty float y\nproperty float z\nend_header\n"
                       "3 0 1 2\n8 0 1 2 3 4 5 6 7\n3 5 6 7\n" +
                           std::string(kUVertices)));
    EXPECT_EQ(fromObj.indices.size(), 6u);
    EXPECT_NEAR(Area(fromObj), 7.0, 1e-9);
    ASSERT_EQ(fromPly.indices.size(), 8u);
    EXPECT_EQ(fromPly.indices[0], glm::uvec3(0, 1, 2));  // in the file's order
    EXPECT_EQ(fromPly.indices[7], glm::uvec3(5, 6, 7));
    EXPECT_EQ(std::vector(fromPly.indices.begin() + 1, fromPly.indices.end() - 1), fromObj.indices);
    for (const TriangleMesh* mesh : {&fromObj, &fromPly})
        for (glm::uvec3 t : mesh->indices) {
            const vec3 centroid =
                (mesh->positions[t.x] + mesh->positions[t.y] + mesh->positions[t.z]) / 3.0f;
            EXPECT_FALSE(centroid.x > 1.0f && centroid.x < 2.0f && centroid.y > 1.0f)
                << "a triangle in the notch";
            const vec3 n = glm::cross(mesh->positions[t.y] - mesh->positions[t.x],
                                      mesh->positions[t.z] - mesh->positions[t.x]);
            EXPECT_GE(n.z, 0.0f);  // the face's winding
        }
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

TEST_F(MeshIoTest, ObjCornersWithoutNormalsGetAreaWeightedNormals) {
    // A triangle of area 2 facing +z, without normals, and one of area 1 facing +x, with them,
    // share vertices 1 and 2: the first one's corners take the area-weighted normals of every
    // face around their vertices, the second one's keep the file's.
    std::string path = Write("weighted.obj",
                             "v 0 0 0\nv 0 2 0\nv -2 0 0\nv 0 0 1\nvn 1 0 0\n"
                             "f 1 2 3\n"
                             "f 1//1 2//1 4//1\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.positions.size(), 6u);  // 1 2 3 without a normal, then 1 2 4 with vn 1
    ASSERT_EQ(mesh.indices.size(), 2u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(mesh.indices[1], glm::uvec3(3, 4, 5));
    ExpectUnitNormals(mesh);
    vec3 expected = glm::normalize(vec3(1.0f, 0.0f, 2.0f));
    EXPECT_NEAR(glm::distance(mesh.normals[0], expected), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(mesh.normals[1], expected), 0.0f, 1e-6f);
    EXPECT_EQ(mesh.normals[2], vec3(0.0f, 0.0f, 1.0f));
    for (int v = 3; v < 6; ++v) EXPECT_EQ(mesh.normals[v], vec3(1.0f, 0.0f, 0.0f));
}

TEST_F(MeshIoTest, ObjWithoutAnyNormalKeepsItsVertices) {
    std::string path = Write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.positions.size(), 4u);
    EXPECT_EQ(mesh.normals[0], vec3(0.0f, 0.0f, 1.0f));
}

TEST_F(MeshIoTest, ObjNormalsWithoutDirectionFallBackPerCorner) {
    // vn 2 is NaN and vn 3 zero: the corners naming them take computed normals, the others
    // keep vn 1 (tilted: the computed normal would be +z). An unused NaN normal is no error.
    std::string path = Write("nan_normal.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                             "vn 0.6 0 0.8\nvn nan nan nan\nvn 0 0 0\nvn inf 0 0\n"
                             "f 1//1 2//1 3//1\n"
                             "f 2//2 4//3 3//1\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.indices.size(), 2u);
    ExpectUnitNormals(mesh);
    const glm::uvec3 second = mesh.indices[1];
    EXPECT_EQ(mesh.normals[second.x], vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(mesh.normals[second.y], vec3(0.0f, 0.0f, 1.0f));
    EXPECT_NEAR(glm::distance(mesh.normals[second.z], vec3(0.6f, 0.0f, 0.8f)), 0.0f, 1e-6f);
    for (int corner = 0; corner < 3; ++corner)
        EXPECT_NEAR(glm::distance(mesh.normals[mesh.indices[0][corner]], vec3(0.6f, 0.0f, 0.8f)),
                    0.0f, 1e-6f);
}

TEST_F(MeshIoTest, ObjStatementsContinueAfterABackslash) {
    std::string path = Write("continued.obj",
                             "v 0 0 0\nv 1 0 0\\\n"
                             "  \nv 1 1 0\nv 0 1 \\  # a comment after the backslash\n"
                             "0\n"
                             "f 1 2 \\\r\n 3 4\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.positions.size(), 4u);
    EXPECT_EQ(mesh.positions[3], vec3(0.0f, 1.0f, 0.0f));
    ASSERT_EQ(mesh.indices.size(), 2u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(mesh.indices[1], glm::uvec3(0, 2, 3));
    // An error in a continued statement names its first line.
    ExpectInputError(Write("continued_error.obj", "v 0 0 0\nv 1 \\\n0 \\\nzero\n"), "line 2",
                     "expected a number, found 'zero'");
    // A statement continued to the end of the file ends there (a face of one corner: skipped).
    EXPECT_EQ(LoadMesh(Write("continued_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 \\\n"))
                  .indices.size(),
              1u);
}

TEST_F(MeshIoTest, ObjDropsDegenerateFacesSilently) {
    std::string path = Write("degenerate.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "f 1 1 2\n"
                             "f 1 2 3 3\n");
    TriangleMesh mesh = LoadMesh(path);
    ASSERT_EQ(mesh.indices.size(), 1u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
}

TEST_F(MeshIoTest, ObjErrors) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    ExpectInputError(Write("range.obj", vertices + "f 1 2 4\n"), "line 4", "out of range");
    // Faces of fewer than 3 corners (loose edges, as older exporters wrote them) are skipped with
    // a warning that counts them; they had been dropped without a word.
    testing::internal::CaptureStderr();
    EXPECT_EQ(LoadMesh(Write("line.obj", vertices + "f 1 2 3\nf 1 2\nf\n")).indices.size(), 1u);
    const std::string warning = testing::internal::GetCapturedStderr();
    EXPECT_NE(warning.find("line.obj: 2 faces of fewer than 3 corners (lines or points, no "
                           "surface) skipped"),
              std::string::npos)
        << warning;
    ExpectInputError(Write("only_lines.obj", vertices + "f 1 2\n"), "", "contains no triangles");
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
    ExpectInputError(Write("inf.obj", "v 0 0 0\nv inf 0 0\n"), "line 2", "NaN or infinite");
    ExpectInputError(Write("huge.obj", "v 0 0 0\nv 1e39 0 0\n"), "line 2",
                     "number '1e39' is beyond the float range");
    ExpectInputError(Write("short.obj", "v 0 0\n"), "line 1", "needs three coordinates");
    ExpectInputError(Write("text.obj", "v 0 zero 0\n"), "line 1", "expected a number");
    ExpectInputError(Write("ply.obj", "ply\nformat ascii 1.0\n"), "line 1",
                     "unknown statement 'ply'");
    ExpectInputError(Write("empty.obj", vertices), "", "contains no triangles");
    ExpectInputError(Write("flat.obj", vertices + "f 1 2 2\n"), "", "contains no triangles");
}

}  // namespace
}  // namespace rtrt
