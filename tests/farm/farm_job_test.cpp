#include "game/farm/farm_job.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "game/farm/job_folder.h"

namespace rtrt {
namespace {
namespace fs = std::filesystem;

class FarmJobTest : public testing::Test {
  protected:
    void SetUp() override {
        folder_ = (fs::temp_directory_path() / ("rtrt_farm_job_test_" + std::to_string(::getpid())))
                      .string();
        fs::remove_all(folder_);
        fs::create_directories(folder_);
    }
    void TearDown() override { fs::remove_all(folder_); }

    void WriteText(const std::string& text) { std::ofstream(FarmFile(folder_)) << text; }
    std::string ReadError() {
        try {
            ReadFarmJob(folder_);
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    }

    std::string folder_;
};

TEST_F(FarmJobTest, WrittenJobReadsBackEqual) {
    FarmJob job;
    job.folder = folder_;
    job.frames = {"/scenes/demo physics.json",
                  "0123456789abcdef",
                  {12, 480},
                  3840,
                  2160,
                  16,
                  29.97,
                  "cuda",
                  "ppm"};
    job.scheduling = {8, true, "gpu", "2:00:00", 4};
    job.submissions = {{"17", "18"}, {"", "21"}};
    WriteFarmJob(job);
    const FarmJob back = ReadFarmJob(folder_);
    EXPECT_EQ(back.frames, job.frames);  // fps 29.97 exactly, as the command line gave it
    EXPECT_EQ(back.scheduling.shards, 8);
    EXPECT_TRUE(back.scheduling.gpu);
    EXPECT_EQ(back.scheduling.partition, "gpu");
    EXPECT_EQ(back.scheduling.timeLimit, "2:00:00");
    EXPECT_EQ(back.scheduling.cpusPerTask, 4);
    EXPECT_EQ(back.submissions, job.submissions);
    EXPECT_FALSE(fs::exists(folder_ + "/.farm.partial" + std::to_string(::getpid()) + ".json"));
}

// A job made before the checksum covered the files a scene brings in holds the scene file's
// own: resumed with the same scene file, it is the same job; with an edited one, it is not.
TEST_F(FarmJobTest, AJobOfTheSceneFilesOwnChecksumResumes) {
    const std::string scene = folder_ + "/scene.json";
    std::ofstream(scene) << "{}\n";
    FarmJob old;
    old.folder = folder_ + "/job";
    fs::create_directories(old.folder);
    old.frames.scene = scene;
    old.frames.sceneChecksum = HexDigest(HashFile(scene));
    old.frames.frames = {0, 4};
    old.frames.width = old.frames.height = 8;
    old.submissions = {{"17", "18"}};
    WriteFarmJob(old);
    FarmJob now = old;
    now.submissions.clear();
    now.frames.sceneChecksum = "00000000000000cc";  // of the scene file and its models
    bool takenUp = false;
    EXPECT_EQ(ResumeOrStart(now, &takenUp).submissions, old.submissions);
    std::ofstream(scene) << "{ }\n";
    EXPECT_THROW(ResumeOrStart(now, &takenUp), InputError);
}

TEST_F(FarmJobTest, DifferencesAreNamed) {
    FarmFrames a{"/s.json", "00000000000000aa", {0, 48}, 320, 180, 1, 60.0, "cpu", "png"};
    FarmFrames b = a;
    EXPECT_EQ(FramesDifference(a, b), "");
    b.width = 640;
    b.spp = 4;
    EXPECT_EQ(FramesDifference(a, b), "size 320x180 there, 640x180 here; spp 1 there, 4 here");
    b = a;
    b.sceneChecksum = "00000000000000bb";
    b.fps = 24000.0 / 1001.0;
    EXPECT_EQ(FramesDifference(a, b),
              "the scene or a file it brings in changed since the job started (scene checksum "
              "00000000000000aa there, "
              "00000000000000bb here); fps 60 there, 23.976023976023978 here");
}

TEST_F(FarmJobTest, MalformedFilesNameTheFieldAndReason) {
    EXPECT_NE(ReadError().find("cannot be read; is " + folder_ + " a folder made by `rtrt farm`?"),
              std::string::npos);
    WriteText(
        "{\"version\": 1, \"scene\": \"s\", \"frames\": [5, 5], \"width\": 2, \"height\": 2}");
    EXPECT_NE(ReadError().find("farm.json: frames: expected [first, end]"), std::string::npos)
        << ReadError();
    WriteText(
        "{\"version\": 1, \"scene\": \"s\", \"frames\": [0.5, 3], \"width\": 2, \"height\": 2}");
    EXPECT_NE(
        ReadError().find("frames: expected an array of integers, got an array whose element 0 "
                         "is 0.5"),
        std::string::npos)
        << ReadError();
    WriteText(
        "{\"version\": 1, \"scene\": \"s\", \"frames\": [0, 5], \"width\": 2, \"height\": 2, "
        "\"backend\": \"auto\"}");
    EXPECT_NE(ReadError().find("backend: expected cpu or cuda"), std::string::npos) << ReadError();
    WriteText(
        "{\"version\": 1, \"scene\": \"s\", \"frames\": [0, 5], \"width\": 2, \"height\": 2, "
        "\"colour\": 1}");
    EXPECT_NE(ReadError().find("colour"), std::string::npos) << ReadError();
    WriteText("[1, 2");
    EXPECT_NE(ReadError().find("malformed JSON"), std::string::npos) << ReadError();
}

// A job of a later layout is not "out of range": the message says which rtrt can read it.
TEST_F(FarmJobTest, NewerVersionIsNamedAsSuch) {
    WriteText(
        "{\"version\": 2, \"scene\": \"s\", \"frames\": [0, 5], \"width\": 2, \"height\": 2}");
    EXPECT_NE(ReadError().find("farm.json: version: the job was written by a newer rtrt (version "
                               "2; this rtrt reads version 1)"),
              std::string::npos)
        << ReadError();
    WriteText(
        "{\"version\": 0, \"scene\": \"s\", \"frames\": [0, 5], \"width\": 2, \"height\": 2}");
    EXPECT_NE(ReadError().find("version: expected 1, got 0"), std::string::npos) << ReadError();
    WriteText("{\"scene\": \"s\", \"frames\": [0, 5], \"width\": 2, \"height\": 2}");
    EXPECT_NE(ReadError().find("version: missing required field"), std::string::npos)
        << ReadError();
}

// farm.json is JSON text, which is UTF-8: a path that is not is refused before anything is
// written, naming the option.
TEST(FarmPath, PathsThatAreNotUtf8AreRefused) {
    EXPECT_NO_THROW(CheckFarmPath("--output", "/tmp/farm/\xc3\xa9t\xc3\xa9"));  // UTF-8
    for (const std::string bad : {"/tmp/out\xff", "/tmp/\xc3", "/tmp/\xc3(x"}) {
        try {
            CheckFarmPath("--output", bad);
            ADD_FAILURE() << "accepted a path that is not UTF-8";
        } catch (const InputError& e) {
            EXPECT_EQ(e.File(), "--output");
            EXPECT_NE(e.Reason().find("not valid UTF-8"), std::string::npos) << e.what();
        }
    }
}

TEST_F(FarmJobTest, FrameFilesHaveSixDigits) {
    FarmJob job;
    job.folder = "/out";
    job.frames.format = "png";
    EXPECT_EQ(FrameFile(job, 42), "/out/frames/frame_000042.png");
    EXPECT_EQ(FramePattern(job), "/out/frames/frame_%06d.png");
}

}  // namespace
}  // namespace rtrt
