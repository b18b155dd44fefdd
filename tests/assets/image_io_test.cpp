// Writing images: an output path that stops being writable between the command's checks and the
// write is a failed write (OutputError, exit 1), as a full disk is, not bad input.
#include "game/assets/image_io.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "engine/core/error.h"
#include "tests/scratch_folder.h"

namespace rtrt {
namespace {

using ImageIoTest = test::ScratchFolderTest;

TEST_F(ImageIoTest, AnOutputFolderGoneByTheWriteIsAFailedWrite) {
    const std::string path = (dir_ / "gone" / "frame.ppm").string();
    std::filesystem::create_directory(dir_ / "gone");
    CheckImagePath(path);  // what a command checks before its work
    std::filesystem::remove(dir_ / "gone");
    Image image(2, 2);
    try {
        WriteImage(path, image);
        FAIL() << "wrote into a missing folder";
    } catch (const OutputError& e) {
        EXPECT_EQ(e.File(), path);
        EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(path));
    // A format rtrt cannot write is still the caller's mistake.
    EXPECT_THROW(WriteImage((dir_ / "frame.nosuchformat").string(), image), InputError);
}

// A name ending in a dot has no extension; it had been named as a format rtrt cannot write (".").
TEST_F(ImageIoTest, ANameEndingInADotNeedsAnExtension) {
    for (const char* name : {"a.png.", "a", "a."}) {
        try {
            CheckImagePath((dir_ / name).string());
            ADD_FAILURE() << name << " passed";
        } catch (const InputError& e) {
            EXPECT_EQ(e.Reason(), "the output needs an extension such as .png or .exr") << name;
        }
    }
    EXPECT_NO_THROW(CheckImagePath((dir_ / "a.ppm").string()));
}

}  // namespace
}  // namespace rtrt
