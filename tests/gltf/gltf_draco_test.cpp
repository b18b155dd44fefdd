// Draco-compressed glTF primitives (KHR_draco_mesh_compression): meshes the test encodes itself
// with libdraco decode to exactly the triangles it started from, in .gltf and .glb files, and a
// stream or accessors that do not match give one error naming the primitive.
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "engine/core/error.h"
#include "game/gltf/gltf_import.h"
#include "tests/gltf/gltf_builder.h"
#include "tests/gltf/gltf_test_dir.h"

namespace rtrt {
namespace {

// One triangle corner: position and uv, comparable.
using Corner = std::array<float, 5>;
using Face = std::array<Corner, 3>;

// The same triangle whichever corner comes first (its winding kept).
Face Canonical(Face f) {
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    return f;
}

// A 4 x 3 grid of quads on a bumpy surface, with uvs: 24 triangles, 20 shared vertices.
std::vector<Face> GridFaces() {
    auto corner = [](int x, int y) {
        const float fx = float(x), fy = float(y);
        return Corner{fx * 0.5f, fy * 0.25f, 0.125f * float((x * 7 + y * 3) % 5), fx / 4.0f,
                      fy / 3.0f};
    };
    std::vector<Face> faces;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            faces.push_back({corner(x, y), corner(x + 1, y), corner(x + 1, y + 1)});
            faces.push_back({corner(x, y), corner(x + 1, y + 1), corner(x, y + 1)});
        }
    return faces;
}

struct DracoStream {
    std::vector<uint8_t> bytes;
    uint32_t positionId, uvId;
    uint32_t points, faces;
};

// FACES encoded losslessly (no quantization) with libdraco's edgebreaker.
DracoStream Encode(const std::vector<Face>& faces) {
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(int(faces.size()));
    const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (size_t f = 0; f < faces.size(); ++f) {
        const Face& face = faces[f];
        builder.SetAttributeValuesForFace(pos, draco::FaceIndex(uint32_t(f)), &face[0][0],
                                          &face[1][0], &face[2][0]);
        builder.SetAttributeValuesForFace(uv, draco::FaceIndex(uint32_t(f)), &face[0][3],
                                          &face[1][3], &face[2][3]);
    }
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    encoder.SetSpeedOptions(5, 5);
    draco::EncoderBuffer buffer;
    EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &buffer).ok());
    DracoStream out;
    out.bytes.assign(buffer.data(), buffer.data() + buffer.size());
    out.positionId = mesh->attribute(pos)->unique_id();
    out.uvId = mesh->attribute(uv)->unique_id();
    out.points = mesh->num_points();
    out.faces = mesh->num_faces();
    return out;
}

// A glTF whose one primitive is the stream: accessors with counts and types but no data.
test::GltfBuilder DracoGltf(const DracoStream& s, int indexType = 5123) {
    test::GltfBuilder b;
    while (b.bin.size() % 4) b.bin.push_back(0);
    const size_t offset = b.bin.size();
    b.bin.insert(b.bin.end(), s.bytes.begin(), s.bytes.end());
    b.doc["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", s.bytes.size()}});
    const size_t view = b.doc["bufferViews"].size() - 1;
    auto accessor = [&](int type, uint32_t count, const char* kind) {
        b.doc["accessors"].push_back({{"componentType", type}, {"count", count}, {"type", kind}});
        return int(b.doc["accessors"].size() - 1);
    };
    const int position = accessor(5126, s.points, "VEC3");
    const int uv = accessor(5126, s.points, "VEC2");
    const int indices = accessor(indexType, s.faces * 3, "SCALAR");
    const int mesh = b.Mesh(position, indices, uv);
    b.doc["meshes"][size_t(mesh)]["primitives"][0]["extensions"] = {
        {"KHR_draco_mesh_compression",
         {{"bufferView", view},
          {"attributes", {{"POSITION", s.positionId}, {"TEXCOORD_0", s.uvId}}}}}};
    b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    b.doc["scenes"] = {{{"nodes", {b.Node({{"mesh", mesh}})}}}};
    return b;
}

std::vector<Face> LoadedFaces(const std::string& path) {
    LoadedScene scene;
    LoadGltfAsset(path, scene);
    EXPECT_EQ(scene.scene.blases.size(), 1u);
    const Blas& blas = *scene.scene.blases.at(0);
    EXPECT_EQ(blas.uvs.size(), blas.triangles.size());
    std::vector<Face> faces;
    for (size_t t = 0; t < blas.triangles.size(); ++t) {
        const Triangle& tri = blas.triangles[t];
        const TriangleUvs& uv = blas.uvs[t];
        auto corner = [](vec3 p, vec2 u) { return Corner{p.x, p.y, p.z, u.x, u.y}; };
        faces.push_back(
            Canonical({corner(tri.v0, uv.uv0), corner(tri.v1, uv.uv1), corner(tri.v2, uv.uv2)}));
    }
    std::sort(faces.begin(), faces.end());
    return faces;
}

using GltfDraco = GltfTest;

TEST_F(GltfDraco, DecodesExactlyTheEncodedTrianglesInEveryContainer) {
    std::vector<Face> expected = GridFaces();
    for (Face& f : expected) f = Canonical(f);
    std::sort(expected.begin(), expected.end());
    const DracoStream stream = Encode(GridFaces());
    ASSERT_EQ(stream.faces, 24u);
    for (int indexType : {5121, 5123, 5125}) {
        const test::GltfBuilder b = DracoGltf(stream, indexType);
        EXPECT_EQ(LoadedFaces(Save("grid.gltf", b.GltfText())), expected) << indexType;
        EXPECT_EQ(LoadedFaces(Save("grid.glb", b.Glb())), expected) << indexType;
    }
}

// A buffer besides the stream's (here an external .bin holding it) keeps working: the decoded
// data goes into a new first buffer and every view shifts.
TEST_F(GltfDraco, StreamInAnExternalBufferDecodes) {
    const DracoStream stream = Encode(GridFaces());
    test::GltfBuilder b = DracoGltf(stream);
    Save("grid.bin", std::string(b.bin.begin(), b.bin.end()));
    nlohmann::json doc = b.doc;
    doc["buffers"] = {{{"byteLength", b.bin.size()}, {"uri", "grid.bin"}}};
    EXPECT_EQ(LoadedFaces(Save("grid.gltf", doc.dump())).size(), 24u);
}

void ExpectError(const std::string& path, const std::string& field, const std::string& reason) {
    try {
        LoadedScene scene;
        LoadGltfAsset(path, scene);
        ADD_FAILURE() << "loaded without an error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.Field(), field) << e.what();
        EXPECT_NE(e.Reason().find(reason), std::string::npos) << e.what();
    }
}

constexpr const char* kField = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";

TEST_F(GltfDraco, MismatchesAreNamed) {
    const DracoStream stream = Encode(GridFaces());
    {
        test::GltfBuilder b = DracoGltf(stream);
        b.doc["accessors"][0]["count"] = stream.points + 1;
        ExpectError(Save("count.gltf", b.GltfText()), std::string(kField) + ".attributes.POSITION",
                    "has count");
    }
    {
        test::GltfBuilder b = DracoGltf(stream);
        b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
             ["attributes"]["POSITION"] = 17;
        ExpectError(Save("id.gltf", b.GltfText()), std::string(kField) + ".attributes.POSITION",
                    "no attribute with this id");
    }
    {
        test::GltfBuilder b = DracoGltf(stream);
        b.doc["accessors"][2]["count"] = stream.faces * 3 - 3;
        ExpectError(Save("indices.gltf", b.GltfText()), std::string(kField) + ".indices",
                    "has count");
    }
    {
        test::GltfBuilder b = DracoGltf(stream);
        b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
             ["bufferView"] = 5;
        ExpectError(Save("view.gltf", b.GltfText()), std::string(kField) + ".bufferView",
                    "names no buffer view");
    }
}

TEST_F(GltfDraco, CorruptStreamIsRefusedNamingThePrimitive) {
    DracoStream stream = Encode(GridFaces());
    for (size_t i = stream.bytes.size() / 3; i < stream.bytes.size(); ++i) stream.bytes[i] ^= 0x5A;
    stream.bytes.resize(stream.bytes.size() / 2);
    ExpectError(Save("corrupt.glb", DracoGltf(stream).Glb()), kField, "libdraco cannot decode");
    stream.bytes = {'D', 'R', 'A', 'C', 'O'};
    ExpectError(Save("short.glb", DracoGltf(stream).Glb()), kField, "libdraco cannot decode");
}

// Debian's assimp-testmodels: a 29-mesh engine whose 34 primitives are all Draco-compressed.
TEST(GltfDracoAssimp, TwoCylinderEngineDecodes) {
    const std::string path = "/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "assimp-testmodels is not installed";
    LoadedScene scene;
    LoadGltfAsset(path, scene);
    // The sums of the file's index and POSITION accessor counts.
    size_t triangles = 0;
    for (const auto& blas : scene.scene.blases) triangles += blas->triangles.size();
    EXPECT_EQ(triangles, 65311u);
    EXPECT_EQ(scene.scene.blases.size(), 34u);
}

}  // namespace
}  // namespace rtrt
