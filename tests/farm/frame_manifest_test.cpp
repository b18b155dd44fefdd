#include "game/farm/frame_manifest.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "engine/core/content_hash.h"

namespace rtrt {
namespace {
namespace fs = std::filesystem;

class FrameManifestTest : public testing::Test {
  protected:
    void SetUp() override {
        job_.folder =
            (fs::temp_directory_path() / ("rtrt_manifest_test_" + std::to_string(::getpid())))
                .string();
        fs::remove_all(job_.folder);
        fs::create_directories(FramesFolder(job_.folder));
        fs::create_directories(ManifestFolder(job_.folder));
        job_.frames.frames = {10, 16};
        job_.frames.format = "ppm";
    }
    void TearDown() override { fs::remove_all(job_.folder); }

    // Frame FRAME's file with CONTENT, and its manifest line in MANIFEST.
    void Finish(int frame, const std::string& content, const std::string& manifest = "a.tsv") {
        std::ofstream(FrameFile(job_, frame), std::ios::binary) << content;
        AppendToManifest(ManifestFolder(job_.folder) + "/" + manifest, frame,
                         FrameFile(job_, frame));
    }

    FarmJob job_;
};

TEST_F(FrameManifestTest, LineHoldsFrameFileBytesAndChecksum) {
    Finish(12, "twelve");
    std::ifstream in(ManifestFolder(job_.folder) + "/a.tsv");
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "12\tframe_000012.ppm\t6\t" + HexDigest(HashBytes("twelve", 6)));
    const auto entries = ReadManifests(ManifestFolder(job_.folder));
    ASSERT_EQ(entries.size(), 1u);
    ASSERT_EQ(entries.at(12).size(), 1u);
    EXPECT_EQ(entries.at(12)[0].bytes, 6u);
    EXPECT_EQ(entries.at(12)[0].hash, HashBytes("twelve", 6));
}

TEST_F(FrameManifestTest, CheckSortsFramesIntoDoneMissingAndCorrupt) {
    for (int f : {10, 11, 12, 13}) Finish(f, "frame " + std::to_string(f), "task0.tsv");
    Finish(14, "frame 14", "task1.tsv");
    std::ofstream(FrameFile(job_, 11), std::ios::binary) << "frame 1X";  // same size, other bytes
    std::ofstream(FrameFile(job_, 12), std::ios::binary) << "short";
    fs::remove(FrameFile(job_, 13));
    std::ofstream(FrameFile(job_, 15), std::ios::binary) << "no manifest line vouches for it";
    const FrameCheck check = CheckFrames(job_);
    EXPECT_EQ(check.done, (std::vector<int>{10, 14}));
    EXPECT_EQ(check.missing, (std::vector<int>{13, 15}));
    EXPECT_EQ(check.corrupt, (std::vector<int>{11, 12}));
}

TEST_F(FrameManifestTest, TornAndMalformedLinesAreIgnored) {
    Finish(10, "ten");
    const std::string path = ManifestFolder(job_.folder) + "/a.tsv";
    std::ofstream(path, std::ios::app) << "11\tframe_000011.ppm\t3\tnot-hex\n"
                                       << "x\ty\n"
                                       << "12\tframe_000012.ppm\t3\t00000000";  // no newline
    const auto entries = ReadManifests(ManifestFolder(job_.folder));
    ASSERT_EQ(entries.size(), 1u);
    EXPECT_EQ(entries.count(10), 1u);
}

TEST_F(FrameManifestTest, AFrameIsDoneWhenAnyOfItsLinesVouchesForIt) {
    Finish(10, "first render");
    Finish(10, "second render, other bytes", "b.tsv");
    EXPECT_EQ(CheckFrames(job_).done, (std::vector<int>{10}));
    // The older line's bytes back again (a task that ran twice): still done.
    std::ofstream(FrameFile(job_, 10), std::ios::binary) << "first render";
    EXPECT_EQ(CheckFrames(job_).done, (std::vector<int>{10}));
}

TEST_F(FrameManifestTest, ALineAppendedAfterACutOneIsKept) {
    const std::string path = ManifestFolder(job_.folder) + "/a.tsv";
    std::ofstream(path) << "10\tframe_000010.ppm\t3";  // a crash cut this line
    Finish(11, "eleven");
    const auto entries = ReadManifests(ManifestFolder(job_.folder));
    ASSERT_EQ(entries.size(), 1u);
    EXPECT_EQ(entries.count(11), 1u);
}

TEST_F(FrameManifestTest, AppendToAFolderThatIsMissingFailsWithTheManifestsName) {
    try {
        AppendToManifest(job_.folder + "/nowhere/m.tsv", 10, FrameFile(job_, 10));
        FAIL() << "expected an error";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find(FrameFile(job_, 10)), std::string::npos)
            << e.what();  // the frame itself is missing first
    }
}

TEST(FramesTextTest, RunsAsRanges) {
    EXPECT_EQ(FramesText({3, 4, 5, 9, 12, 13}), "3-5, 9, 12-13");
    EXPECT_EQ(FramesText({1, 3, 5, 7}, 2), "1, 3, ...");
    EXPECT_EQ(FramesText({}), "");
}

}  // namespace
}  // namespace rtrt
