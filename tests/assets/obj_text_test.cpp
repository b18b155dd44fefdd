// How OBJ text is read around its statements: every kind of line end, a byte order mark before
// the first line, and control characters in the messages.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "game/assets/mesh_io.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

class ObjTextTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("rtrt_obj_text_" + std::to_string(getpid()) + "_" + info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string Write(const std::string& name, const std::string& contents) {
        const std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary) << contents;
        return path;
    }

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

    fs::path dir_;
};

// LF, CRLF, a lone CR (old Mac files, which read as one line) and a UTF-8 byte order mark (which
// read as an unknown statement) give the same mesh.
TEST_F(ObjTextTest, EveryLineEndAndAByteOrderMarkReadTheSame) {
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
TEST_F(ObjTextTest, LineNumbersFollowEveryLineEnd) {
    std::string field;
    EXPECT_NE(
        Error(Write("cr.obj", "v 0 0 0\r\nv 1 0 0\rv 0 x 0\n"), &field).find("expected a number"),
        std::string::npos);
    EXPECT_EQ(field, "line 3");
}

// Control characters are shown escaped: a NUL had ended the message before its quote.
TEST_F(ObjTextTest, ControlCharactersInMessagesAreEscaped) {
    std::string field;
    EXPECT_EQ(Error(Write("nul.obj", std::string("v 0 0\0x 0\n", 10)), &field),
              "expected a number, found '0\\x00x'");
    EXPECT_EQ(field, "line 1");
}

}  // namespace
}  // namespace rtrt
