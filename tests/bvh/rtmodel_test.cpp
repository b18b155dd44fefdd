// .rtmodel files: a written BLAS reads back bit for bit, and every malformed file in the hostile
// corpus (tests/data/hostile/, made by MakeHostileCorpus below) gives an InputError naming the
// field at fault.
#include "engine/bvh/blas/rtmodel.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "engine/bvh/blas/blas_check.h"
#include "engine/bvh/blas/rtmodel_format.h"
#include "engine/core/error.h"
#include "engine/geometry/smooth_normals.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;
using namespace rtmodel;

template <typename A, typename B>
bool SameBytes(const A& a, const B& b) {
    // memcmp must not see the null data() of an empty vector, even for zero bytes.
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

void ExpectIdentical(const Blas& a, const Blas& b) {
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_TRUE(SameBytes(a.nodes, b.nodes));
    EXPECT_TRUE(SameBytes(a.nodes4, b.nodes4));
    EXPECT_TRUE(SameBytes(a.triangles, b.triangles));
    EXPECT_TRUE(SameBytes(a.normals, b.normals));
    EXPECT_TRUE(SameBytes(a.spheres, b.spheres));
    EXPECT_TRUE(SameBytes(a.primIds, b.primIds));
    EXPECT_TRUE(SameBytes(a.uvs, b.uvs));
    EXPECT_TRUE(SameBytes(a.colors, b.colors));
    EXPECT_EQ(std::memcmp(&a.bounds, &b.bounds, sizeof(Aabb)), 0);
}

std::string ReadBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void WriteBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

class RtModelTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("rtrt_rtmodel_" + std::to_string(getpid()) + "_" + info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string Path(const std::string& name) const { return (dir_ / name).string(); }

    fs::path dir_;
};

// The model every hostile case starts from: 40 random triangles with smooth normals and texture
// coordinates.
Blas CorpusBlas() {
    TriangleMesh mesh = test::RandomTriangles(40, 7);
    ComputeSmoothNormals(mesh);
    for (const vec3& p : mesh.positions) mesh.uvs.push_back(vec2(p.x, p.z));
    for (const vec3& p : mesh.positions) mesh.colors.push_back(glm::fract(p));
    return BuildTriangleBlas(mesh);
}

RtModelInfo CorpusInfo() {
    RtModelInfo info;
    info.key = MakeRtModelKey(0x1234, BvhBuildOptions{});
    info.sourceVertexCount = 120;
    info.sourceBounds = {vec3(-1.0f), vec3(1.0f)};
    info.sahCost = 1.0f;
    return info;
}

TEST_F(RtModelTest, RoundTripIsBitIdentical) {
    const Blas blas = CorpusBlas();
    ASSERT_EQ(blas.colors.size(), blas.PrimCount());
    RtModelInfo info = CorpusInfo();
    WriteRtModel(Path("m.rtmodel"), blas, info);
    RtModelInfo read;
    const Blas back = ReadRtModel(Path("m.rtmodel"), &read);
    ExpectIdentical(blas, back);
    EXPECT_EQ(read.key, info.key);
    EXPECT_EQ(read.sourceVertexCount, 120u);
    EXPECT_EQ(read.sourceBounds.min, vec3(-1.0f));
    EXPECT_EQ(read.sahCost, 1.0f);
    EXPECT_EQ(read.fileBytes, fs::file_size(Path("m.rtmodel")));
    EXPECT_EQ(ReadRtModelInfo(Path("m.rtmodel")).key, info.key);
    // No temporary file is left beside it.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

// Colours, like uvs, are one triple per triangle or none, and no part of a sphere model.
TEST_F(RtModelTest, ColoursAreOnePerTriangleOrNone) {
    Blas blas = CorpusBlas();
    blas.colors.pop_back();
    try {
        CheckBlas(blas, "m.rtmodel");
        ADD_FAILURE() << "a missing colour triple was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.Field(), "colors") << e.what();
        EXPECT_NE(e.Reason().find("expected 0 or 40 colour triples, got 39"), std::string::npos)
            << e.what();
    }
    const Sphere sphere{vec3(0.0f), 1.0f};
    Blas ball = BuildSphereBlas(std::span(&sphere, 1));
    ball.colors.resize(1);
    try {
        CheckBlas(ball, "m.rtmodel");
        ADD_FAILURE() << "a sphere model with colours was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.Field(), "kind") << e.what();
    }
}

// A model near the float limit: every plane of its box is finite, though their sum is not (the
// check once added them up and refused what convert had just written).
TEST_F(RtModelTest, ModelNearTheFloatLimitRoundTrips) {
    TriangleMesh mesh;
    mesh.positions = {vec3(1.2e38f), vec3(1.3e38f, 1.2e38f, 1.2e38f),
                      vec3(1.2e38f, 1.3e38f, 1.2e38f)};
    mesh.indices = {glm::uvec3(0, 1, 2)};
    ComputeSmoothNormals(mesh);
    const Blas blas = BuildTriangleBlas(mesh);
    RtModelInfo info = CorpusInfo();
    info.sourceBounds = {vec3(1.2e38f), vec3(1.3e38f, 1.3e38f, 1.2e38f)};
    WriteRtModel(Path("far.rtmodel"), blas, info);
    RtModelInfo read;
    ExpectIdentical(blas, ReadRtModel(Path("far.rtmodel"), &read));
    EXPECT_EQ(read.sourceBounds.max, info.sourceBounds.max);
}

TEST_F(RtModelTest, SpheresRoundTrip) {
    const std::vector<Sphere> spheres{{vec3(0.0f), 1.0f}, {vec3(3.0f, 0.0f, 0.0f), 0.5f}};
    const Blas blas = BuildSphereBlas(spheres);
    WriteRtModel(Path("s.rtmodel"), blas, CorpusInfo());
    ExpectIdentical(blas, ReadRtModel(Path("s.rtmodel")));
}

TEST_F(RtModelTest, WritingIntoAMissingFolderIsAnInputError) {
    EXPECT_THROW(WriteRtModel(Path("no/such/folder/m.rtmodel"), CorpusBlas(), CorpusInfo()),
                 InputError);
    EXPECT_FALSE(fs::exists(Path("no")));
}

// A FIFO named like a model (in a scene, or in the model cache) is refused at once instead of
// waiting in open() for a writer.
TEST_F(RtModelTest, AFifoIsRefusedWithoutWaiting) {
    const std::string fifo = Path("pipe.rtmodel");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    try {
        ReadRtModelInfo(fifo);
        ADD_FAILURE() << "read a FIFO";
    } catch (const InputError& e) {
        EXPECT_EQ(e.Reason(), "not a regular file") << e.what();
    }
}

TEST(RtModelPath, RecognisesTheExtension) {
    EXPECT_TRUE(IsRtModelPath("a/b.rtmodel"));
    EXPECT_TRUE(IsRtModelPath("B.RTMODEL"));
    EXPECT_FALSE(IsRtModelPath("b.ply.gz"));
    EXPECT_FALSE(IsRtModelPath("rtmodel"));
}

// ---------------------------------------------------------------------------------------------
// The hostile corpus

struct HostileCase {
    std::string name;
    std::string bytes;
    std::string field;   // what the InputError must name
    std::string reason;  // a piece of its reason
};

RtModelHeader HeaderOf(const std::string& bytes) {
    RtModelHeader h;
    std::memcpy(&h, bytes.data(), sizeof(h));
    return h;
}

void PutHeader(std::string& bytes, const RtModelHeader& h) {
    std::memcpy(bytes.data(), &h, sizeof(h));
}

// Edits a field of the header and makes its checksum right again, so that the reader gets past
// the checksum to the field itself.
template <typename Edit>
std::string EditHeader(std::string bytes, Edit edit) {
    RtModelHeader h = HeaderOf(bytes);
    edit(h);
    SealHeader(h);
    PutHeader(bytes, h);
    return bytes;
}

// Edits an element of a payload array and makes both checksums right again, so that the reader
// gets to the structural checks.
template <typename T, typename Edit>
std::string EditPayload(std::string bytes, Section section, size_t index, Edit edit) {
    RtModelHeader h = HeaderOf(bytes);
    const uint64_t at = LayoutOf(h.counts).offset[section] + index * sizeof(T);
    T value;
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    edit(value);
    std::memcpy(bytes.data() + at, &value, sizeof(T));
    h.payloadChecksum = PayloadChecksumOf(bytes.data(), LayoutOf(h.counts));
    SealHeader(h);
    PutHeader(bytes, h);
    return bytes;
}

// The index of the first leaf and of the first interior node after the root.
uint32_t FirstNode(const Blas& blas, bool leaf) {
    for (uint32_t i = 2; i < blas.nodes.size(); ++i)
        if (blas.nodes[i].IsLeaf() == leaf) return i;
    return 0;
}

std::vector<HostileCase> MakeHostileCorpus(const std::string& valid, const Blas& blas) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const uint32_t leaf = FirstNode(blas, true), interior = FirstNode(blas, false);
    std::string flipped = valid;
    flipped[LayoutOf(HeaderOf(valid).counts).offset[kTriangles] + 5] ^= 0x10;
    std::string badHeader = valid;
    badHeader[offsetof(RtModelHeader, reserved) + 3] ^= 1;
    auto node = [&](uint32_t i, auto edit) { return EditPayload<BvhNode>(valid, kNodes, i, edit); };
    return {
        {"empty", "", "header", "truncated"},
        {"truncated_header", valid.substr(0, 100), "header", "truncated"},
        {"truncated_payload", valid.substr(0, valid.size() - 70), "header.fileBytes",
         "(truncated)"},
        {"trailing_bytes", valid + std::string(64, '\0'), "header.fileBytes", "the file has"},
        {"wrong_magic", "GLTF" + valid.substr(4), "header.magic", "not an .rtmodel file"},
        {"wrong_version", EditHeader(valid, [](RtModelHeader& h) { h.version = 99; }),
         "header.version", "version 99"},
        {"bad_header_checksum", badHeader, "header.headerChecksum", "checksum mismatch"},
        {"huge_count",
         EditHeader(valid, [](RtModelHeader& h) { h.counts[kTriangles] = uint64_t(1) << 60; }),
         "header.counts.triangles", "cannot fit"},
        {"unknown_kind", EditHeader(valid, [](RtModelHeader& h) { h.kind = 7; }), "header.kind",
         "unknown geometry kind 7"},
        {"unknown_builder", EditHeader(valid, [](RtModelHeader& h) { h.builder = 9; }),
         "header.builder", "unknown builder id 9"},
        {"nan_source_bounds",
         EditHeader(valid, [&](RtModelHeader& h) { h.sourceBoundsMax[1] = nan; }),
         "header.sourceBounds", "not finite"},
        {"bad_payload_checksum", flipped, "payloadChecksum", "checksum mismatch"},
        {"kind_mismatch", EditHeader(valid, [](RtModelHeader& h) { h.kind = 1; }), "spheres",
         "0 spheres but 40 primIds"},
        {"child_out_of_range", node(0, [](BvhNode& n) { n.leftFirst = 1000000; }),
         "nodes[0].leftFirst", "child index 1000000 out of range"},
        {"child_pair_odd", node(0, [](BvhNode& n) { n.leftFirst = 1; }), "nodes[0].leftFirst",
         "child pair at odd index 1"},
        {"child_cycle", node(interior, [](BvhNode& n) { n.leftFirst = 0; }),
         "nodes[" + std::to_string(interior) + "].leftFirst", "child index 0 out of range"},
        // An interior node made a leaf: its children stay, linked from nowhere (refits, which
        // run over every node, read them).
        {"unreachable_nodes",
         node(interior,
              [](BvhNode& n) {
                  n.leftFirst = 0;
                  n.primCount = 1;
              }),
         "nodes[" + std::to_string(blas.nodes[interior].leftFirst) + "]", "no node links to it"},
        {"leaf_out_of_range", node(leaf, [](BvhNode& n) { n.leftFirst = 40; }),
         "nodes[" + std::to_string(leaf) + "]", "out of range (40 primitives)"},
        {"huge_leaf", node(leaf, [](BvhNode& n) { n.primCount = 0xffffffffu; }),
         "nodes[" + std::to_string(leaf) + "]", "out of range (40 primitives)"},
        {"nan_node_bounds", node(0, [&](BvhNode& n) { n.boundsMin.x = nan; }), "nodes[0]",
         "not finite"},
        {"nodes4_child_out_of_range",
         EditPayload<Bvh4Node>(valid, kNodes4, 0,
                               [](Bvh4Node& n) {
                                   n.count[0] = 0;
                                   n.child[0] = 5000;
                               }),
         "nodes4[0].child[0]", "child index 5000 out of range"},
        {"nan_vertex",
         EditPayload<Triangle>(valid, kTriangles, 3, [&](Triangle& t) { t.v1.y = nan; }),
         "triangles[3]", "NaN or infinite"},
        {"inf_vertex",
         EditPayload<Triangle>(valid, kTriangles, 0, [&](Triangle& t) { t.v0.x = inf; }),
         "triangles[0]", "NaN or infinite"},
        {"nan_uv", EditPayload<TriangleUvs>(valid, kUvs, 7, [&](TriangleUvs& t) { t.uv1.x = nan; }),
         "uvs[7]", "NaN or infinite"},
        {"uv_count_mismatch",
         EditHeader(valid,
                    [](RtModelHeader& h) {
                        // One uv triple fewer: the padding to 64 bytes keeps the file size
                        // and the payload checksum, so the count check catches it.
                        h.counts[kUvs] -= 1;
                    }),
         "uvs", "expected 0 or 40 uv triples, got 39"},
        {"prim_id_out_of_range",
         EditPayload<uint32_t>(valid, kPrimIds, 5, [](uint32_t& id) { id = 1000000; }),
         "primIds[5]", "primitive index 1000000 out of range"},
        {"prim_id_twice",
         EditPayload<uint32_t>(valid, kPrimIds, 1, [&](uint32_t& id) { id = blas.primIds[0]; }),
         "primIds[1]", "listed twice"},
    };
}

std::string ValidCorpusFile(const std::string& dir) {
    const std::string path = dir + "/valid.rtmodel";
    WriteRtModel(path, CorpusBlas(), CorpusInfo());
    return ReadBytes(path);
}

void ExpectRejected(const std::string& path, const HostileCase& c) {
    try {
        ReadRtModel(path);
        ADD_FAILURE() << c.name << ": read without an error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.File(), path) << c.name;
        EXPECT_EQ(e.Field(), c.field) << c.name << ": " << e.what();
        EXPECT_NE(e.Reason().find(c.reason), std::string::npos) << c.name << ": " << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << c.name;
    }
}

TEST_F(RtModelTest, EveryHostileCaseGivesItsError) {
    const std::string valid = ValidCorpusFile(dir_.string());
    for (const HostileCase& c : MakeHostileCorpus(valid, CorpusBlas())) {
        const std::string path = Path(c.name + ".rtmodel");
        WriteBytes(path, c.bytes);
        ExpectRejected(path, c);
    }
}

// The committed corpus (read by the CLI test) is this generator's output. To write it again
// after a format change: RTRT_WRITE_HOSTILE_CORPUS=1 rtrt_bvh_tests --gtest_filter='*Committed*'
TEST_F(RtModelTest, CommittedHostileCorpusIsCurrent) {
    const std::string corpus = test::SourcePath("tests/data/hostile");
    const std::string valid = ValidCorpusFile(dir_.string());
    const bool write = std::getenv("RTRT_WRITE_HOSTILE_CORPUS") != nullptr;
    if (write) WriteBytes(corpus + "/valid.rtmodel", valid);
    EXPECT_EQ(ReadBytes(corpus + "/valid.rtmodel"), valid);
    for (const HostileCase& c : MakeHostileCorpus(valid, CorpusBlas())) {
        const std::string path = corpus + "/" + c.name + ".rtmodel";
        if (write) WriteBytes(path, c.bytes);
        EXPECT_EQ(ReadBytes(path), c.bytes) << path << " is stale; see this test's comment";
        ExpectRejected(path, c);
    }
}

// A file beyond 2 GiB is refused before its sections are allocated: a sparse one takes a few
// kilobytes of disk.
TEST_F(RtModelTest, AFileBeyondTwoGibibytesIsRefusedBeforeItIsRead) {
    const std::string path = Path("sparse.rtmodel");
    WriteBytes(path, ValidCorpusFile(dir_.string()));
    fs::resize_file(path, (uint64_t(3) << 30));
    try {
        ReadRtModel(path);
        ADD_FAILURE() << "a 3 GiB file was read";
    } catch (const InputError& e) {
        EXPECT_NE(e.Reason().find("at most 2 GiB"), std::string::npos) << e.what();
    }
}

TEST_F(RtModelTest, EveryTruncationIsRejected) {
    const std::string valid = ValidCorpusFile(dir_.string());
    for (size_t size = 0; size < valid.size(); size += 97) {
        WriteBytes(Path("t.rtmodel"), valid.substr(0, size));
        EXPECT_THROW(ReadRtModel(Path("t.rtmodel")), InputError) << size;
    }
}

// A single-bit flip anywhere in the file (every 53rd byte here) is caught (by a checksum or a field
// check).
TEST_F(RtModelTest, EveryBitFlipIsRejected) {
    const std::string valid = ValidCorpusFile(dir_.string());
    for (size_t byte = 0; byte < valid.size(); byte += 53) {
        std::string bytes = valid;
        bytes[byte] ^= char(1 << (byte % 8));
        WriteBytes(Path("f.rtmodel"), bytes);
        EXPECT_THROW(ReadRtModel(Path("f.rtmodel")), InputError) << "byte " << byte;
    }
}

// With several defects the checks, which run in parallel, still report the same one every time.
TEST_F(RtModelTest, SeveralDefectsGiveTheSameMessageEveryTime) {
    const std::string valid = ValidCorpusFile(dir_.string());
    std::string bytes = EditPayload<Triangle>(valid, kTriangles, 2, [](Triangle& t) {
        t.v0.z = std::numeric_limits<float>::quiet_NaN();
    });
    bytes = EditPayload<uint32_t>(bytes, kPrimIds, 7, [](uint32_t& id) { id = 99999; });
    bytes = EditPayload<BvhNode>(bytes, kNodes, 0, [](BvhNode& n) { n.boundsMax.y = -1e30f; });
    WriteBytes(Path("several.rtmodel"), bytes);
    for (int i = 0; i < 20; ++i) {
        try {
            ReadRtModel(Path("several.rtmodel"));
            ADD_FAILURE() << "read without an error";
        } catch (const InputError& e) {
            ASSERT_EQ(e.Field(), "nodes[0]") << e.what();
        }
    }
}

TEST_F(RtModelTest, MissingFileAndFolderAreInputErrors) {
    EXPECT_THROW(ReadRtModel(Path("none.rtmodel")), InputError);
    EXPECT_THROW(ReadRtModel(dir_.string()), InputError);
}

}  // namespace
}  // namespace rtrt
