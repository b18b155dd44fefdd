// How OBJ and PLY text is read around its statements: every kind of line end, a byte order mark
// before the first line, and control characters in the messages.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/error.h"
#include "game/assets/mesh_io.h"
#include "tests/scratch_folder.h"

namespace rtrt {
namespace {

class ModelTextTest : public test::ScratchFolderTest {
  protected:
    // The reason of the InputError the file gives, with its field.
    static std::string Error(const std::string& path, std::string* field) {
        try {
            LoadMesh(path);
        } catch (const InputError& e) {
            *field = e.Field();
            return e.Reason();
        }
        return "";
    }
};

// LF, CRLF, a lone CR (old Mac files, which read as one line) and a UTF-8 byte order mark (which
// read as an unknown statement) give the same mesh.
TEST_F(ModelTextTest, EveryLineEndAndAByteOrderMarkReadTheSame) {
    const std::string lf = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const TriangleMesh expected = LoadMesh(Write("lf.obj", lf));
    auto replaced = [&](const std::string& end) {
        std::string text;
        for (char c : lf) text += c == '\n' ? end : std::string(1, c);
        return text;
    };
    for (const std::string& text :
         {replaced("\r\n"), replaced("\r"), "\xEF\xBB\xBF" + lf, "\xEF\xBB\xBF" + replaced("\r")}) {
        const TriangleMesh mesh = LoadMesh(Write("ends.obj", text));
        EXPECT_EQ(mesh.positions, expected.positions);
        EXPECT_EQ(mesh.indices, expected.indices);
    }
}

// Line numbers count a CRLF once and a lone CR as a line.
TEST_F(ModelTextTest, LineNumbersFollowEveryLineEnd) {
    std::string field;
    EXPECT_NE(
        Error(Write("cr.obj", "v 0 0 0\r\nv 1 0 0\rv 0 x 0\n"), &field).find("expected a number"),
        std::string::npos);
    EXPECT_EQ(field, "line 3");
}

// Control characters are shown escaped: a NUL had ended the message before its quote.
TEST_F(ModelTextTest, ControlCharactersInMessagesAreEscaped) {
    std::string field;
    EXPECT_EQ(Error(Write("nul.obj", std::string("v 0 0\0x 0\n", 10)), &field),
              "expected a number, found '0\\x00x'");
    EXPECT_EQ(field, "line 1");
}

// A PLY header's lines end as its first does: LF, CRLF or a lone CR (which had read as one line
// without end_header), for an ASCII body and for a binary one whose first byte is a line feed.
TEST_F(ModelTextTest, PlyHeadersOfEveryLineEndReadTheSame) {
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    auto ended = [](const std::string& text, const std::string& end) {
        std::string out;
        for (char c : text) out += c == '\n' ? end : std::string(1, c);
        return out;
    };
    const TriangleMesh expected = LoadMesh(Write("lf.ply", header + body));
    for (const char* end : {"\r\n", "\r"}) {
        const TriangleMesh mesh = LoadMesh(Write("ends.ply", ended(header + body, end)));
        EXPECT_EQ(mesh.positions, expected.positions);
        EXPECT_EQ(mesh.indices, expected.indices);
    }
    // Binary: three vertices of one uchar each, the first 10 (a line feed), then the face.
    std::string binary = ended(header, "\r");
    binary.replace(binary.find("ascii"), 5, "binary_little_endian");
    for (const char* name : {"x", "y", "z"})
        binary.replace(binary.find(std::string("float ") + name), 5, "uchar");
    const std::string bytes(
        "\x0A\x00\x00"
        "\x00\x00\x00"
        "\x00\x01\x00"
        "\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00",
        22);
    const TriangleMesh mesh = LoadMesh(Write("binary.ply", binary + bytes));
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.positions[0], glm::vec3(10.0f, 0.0f, 0.0f));
    EXPECT_EQ(mesh.positions[2], glm::vec3(0.0f, 1.0f, 0.0f));
    ASSERT_EQ(mesh.indices.size(), 1u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
}

}  // namespace
}  // namespace rtrt
