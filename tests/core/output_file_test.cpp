// Where whole files may be written: checked paths, and targets that a rename must not replace.
#include "engine/core/output_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "engine/core/error.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

class OutputPathTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("rtrt_output_path_" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        fifo_ = (dir_ / "pipe.json").string();
        ASSERT_EQ(::mkfifo(fifo_.c_str(), 0600), 0);
    }
    void TearDown() override { fs::remove_all(dir_); }

    static std::string Reason(const std::string& path) {
        try {
            CheckOutputPath(path);
        } catch (const InputError& e) {
            EXPECT_EQ(e.File(), path);
            return e.Reason();
        }
        return "";
    }

    fs::path dir_;
    std::string fifo_;
};

TEST_F(OutputPathTest, CheckOutputPathNamesWhatIsWrong) {
    EXPECT_EQ(Reason((dir_ / "new.json").string()), "");
    WriteWholeFile((dir_ / "old.json").string(), "{}\n", false);
    EXPECT_EQ(Reason((dir_ / "old.json").string()), "");  // replaced whole
    EXPECT_EQ(Reason((dir_ / "no" / "r.json").string()),
              "the folder " + (dir_ / "no").string() + " does not exist");
    EXPECT_EQ(Reason(dir_.string()), "is a folder; name a file in it");
    EXPECT_EQ(Reason(fifo_), "is not a regular file (a device, FIFO or socket)");
    EXPECT_EQ(Reason("/dev/null"), "is not a regular file (a device, FIFO or socket)");
}

// Even without the check up front, a write never renames a file over a FIFO or a folder.
TEST_F(OutputPathTest, AWriteDoesNotReplaceAFifoOrAFolder) {
    for (const std::string& target : {fifo_, dir_.string()}) {
        EXPECT_THROW(WriteWholeFile(target, "{}\n", false), InputError) << target;
    }
    struct stat st {};
    ASSERT_EQ(::stat(fifo_.c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(OutputPathTest, CreateOutputFolderRefusesAFileInTheWay) {
    CreateOutputFolder((dir_ / "a" / "b").string());
    EXPECT_TRUE(fs::is_directory(dir_ / "a" / "b"));
    EXPECT_THROW(CreateOutputFolder(fifo_), InputError);
    EXPECT_THROW(CreateOutputFolder((dir_ / "pipe.json" / "x").string()), InputError);
}

}  // namespace
}  // namespace rtrt
