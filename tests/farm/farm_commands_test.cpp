// The batch scripts run as Slurm runs them, with SLURM_* set and stand-ins for rtrt and scontrol
// on PATH; the real cluster runs them in tests/farm/slurm_farm_test.py.
#include "game/farm/farm_commands.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/core/child_process.h"

namespace rtrt {
namespace {
namespace fs = std::filesystem;

class FarmScriptTest : public testing::Test {
  protected:
    void SetUp() override {
        dir_ = (fs::temp_directory_path() / ("rtrt_farm_script_test_" + std::to_string(::getpid())))
                   .string();
        fs::remove_all(dir_);
        fs::create_directories(dir_ + "/bin");
        job_.folder = dir_ + "/out dir";  // a space, as users' folders have
        job_.frames = {"/scenes/it's.json", "", {0, 48}, 320, 180, 4, 30.0, "cpu", "png"};
        job_.scheduling.shards = 2;
        // The stand-in rtrt logs its arguments, one per line, and exits with $FAKE_STATUS.
        Executable("rtrt", "printf '%s\\n' \"$@\" >> \"$FAKE_LOG\"; exit ${FAKE_STATUS:-0}\n");
        Executable("scontrol", "echo \"scontrol $*\" >> \"$FAKE_LOG\"\n");
    }
    void TearDown() override { fs::remove_all(dir_); }

    void Executable(const std::string& name, const std::string& body) {
        const std::string path = dir_ + "/bin/" + name;
        std::ofstream(path) << "#!/bin/bash\n" << body;
        ::chmod(path.c_str(), 0755);
    }

    // Runs SCRIPT as array element TASK (restart count RESTARTS); the stand-ins' log.
    std::string RunElement(const std::string& script, int task, int status, int restarts,
                           int* exitStatus) {
        const std::string path = dir_ + "/job.sbatch", log = dir_ + "/log.txt";
        std::ofstream(path) << script;
        fs::remove(log);
        ChildOptions o;
        o.environment = {{"PATH", dir_ + "/bin:/usr/bin:/bin"},
                         {"SLURM_ARRAY_JOB_ID", "77"},
                         {"SLURM_ARRAY_TASK_ID", std::to_string(task)},
                         {"SLURM_RESTART_COUNT", std::to_string(restarts)},
                         {"FAKE_STATUS", std::to_string(status)},
                         {"FAKE_LOG", log}};
        std::string output;
        *exitStatus = RunProgram({"/bin/bash", path}, &output, o);
        std::ifstream in(log);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    }

    std::string dir_;
    FarmJob job_;
};

TEST_F(FarmScriptTest, ShellQuoteKeepsEveryCharacter) {
    EXPECT_EQ(ShellQuote("plain/path_1.json"), "plain/path_1.json");
    EXPECT_EQ(ShellQuote("it's here"), "'it'\\''s here'");
    EXPECT_EQ(ShellQuote(""), "''");
    std::string echoed;
    RunProgram({"/bin/bash", "-c", "printf %s " + ShellQuote("a 'b' $c \"d\" `e`")}, &echoed);
    EXPECT_EQ(echoed, "a 'b' $c \"d\" `e`");
}

TEST_F(FarmScriptTest, RenderScriptAsksSlurmForTheArray) {
    const std::string s = RenderScript(job_, {{{0, 24}}, {{24, 30}, {40, 48}}}, "/opt/rtrt");
    EXPECT_NE(s.find("#SBATCH --array=0-1\n"), std::string::npos);
    EXPECT_NE(s.find("#SBATCH --requeue\n"), std::string::npos);
    EXPECT_NE(s.find("#SBATCH --output=" + job_.folder + "/logs/render-%A_%a.log\n"),
              std::string::npos);
    EXPECT_EQ(s.find("--gres"), std::string::npos);
    job_.scheduling.gpu = true;
    job_.scheduling.partition = "render";
    const std::string gpu = RenderScript(job_, {{{0, 48}}}, "/opt/rtrt");
    EXPECT_NE(gpu.find("#SBATCH --gres=gpu:1\n"), std::string::npos);
    EXPECT_NE(gpu.find("#SBATCH --partition=render\n"), std::string::npos);
}

TEST_F(FarmScriptTest, ElementRendersItsRangesWithItsOwnManifest) {
    const std::string script =
        RenderScript(job_, {{{0, 24}}, {{24, 30}, {40, 48}}}, dir_ + "/bin/rtrt");
    int status = -1;
    const std::string log = RunElement(script, 1, 0, 0, &status);
    EXPECT_EQ(status, 0);
    const std::string manifest = job_.folder + "/manifest/render-77_1.tsv";
    const std::string expected =
        "play\n/scenes/it's.json\n--headless\n--frames\n24:30\n--size\n320x180\n--spp\n4\n"
        "--fps\n30\n--backend\ncpu\n-o\n" +
        job_.folder + "/frames/frame_%06d.png\n--manifest\n" + manifest + "\n";
    EXPECT_EQ(log, expected + expected.substr(0, expected.find("24:30")) + "40:48" +
                       expected.substr(expected.find("24:30") + 5));
}

// A requeued element goes on after the frames its manifest lists in whole lines: frames 80 to
// 117 of a killed element had been rendered again.
TEST_F(FarmScriptTest, RequeuedElementGoesOnAfterTheFramesItsManifestLists) {
    const std::string script =
        RenderScript(job_, {{{0, 24}}, {{24, 30}, {40, 48}}}, dir_ + "/bin/rtrt");
    const std::string manifest = job_.folder + "/manifest/render-77_1.tsv";
    fs::create_directories(job_.folder + "/manifest");
    {
        std::ofstream out(manifest);
        for (int frame = 24; frame < 30; ++frame)  // the first range whole
            out << frame << "\tframe_0000" << frame << ".png\t100\t00000000000000aa\n";
        out << "40\tframe_000040.png\t100\t00000000000000aa\n";
        out << "42\tframe_000042.png\t100\t00000000000000aa\n";  // not in order: 41 is due
        out << "41\tframe_000041.png\t10";                       // cut short by a crash
    }
    int status = -1;
    const std::string log = RunElement(script, 1, 0, 1, &status);
    EXPECT_EQ(status, 0);
    EXPECT_EQ(log.find("24:30"), std::string::npos) << log;
    EXPECT_NE(log.find("--frames\n41:48\n"), std::string::npos) << log;
    EXPECT_EQ(log.find("play\n"), log.rfind("play\n")) << "one play command: " << log;
}

// A job made from a scene file passes its checksum, so that a task refuses an edited scene.
TEST_F(FarmScriptTest, TasksCarryTheScenesChecksum) {
    std::vector<std::string> command = PlayCommand(job_, "rtrt", {0, 4}, "m.tsv");
    EXPECT_EQ(std::count(command.begin(), command.end(), "--scene-checksum"), 0);
    job_.frames.sceneChecksum = "00000000000000aa";
    command = PlayCommand(job_, "rtrt", {0, 4}, "m.tsv");
    ASSERT_GE(command.size(), 2u);
    EXPECT_EQ(command[command.size() - 2], "--scene-checksum");
    EXPECT_EQ(command.back(), "00000000000000aa");
}

TEST_F(FarmScriptTest, FailedElementRequeuesItselfUpToTheLimit) {
    const std::string script = RenderScript(job_, {{{0, 24}}, {{24, 48}}}, dir_ + "/bin/rtrt");
    int status = -1;
    std::string log = RunElement(script, 0, 1, 0, &status);
    EXPECT_EQ(status, 1);
    EXPECT_NE(log.find("scontrol requeue 77_0\n"), std::string::npos) << log;
    log = RunElement(script, 0, 134, kTaskRequeues - 1, &status);  // a crash
    EXPECT_NE(log.find("scontrol requeue 77_0\n"), std::string::npos) << log;
    log = RunElement(script, 0, 1, kTaskRequeues, &status);  // requeued often enough
    EXPECT_EQ(log.find("scontrol"), std::string::npos) << log;
    log = RunElement(script, 0, 2, 0, &status);  // bad input fails again: no requeue
    EXPECT_EQ(status, 2);
    EXPECT_EQ(log.find("scontrol"), std::string::npos) << log;
    log = RunElement(script, 5, 0, 0, &status);  // an element the array does not have
    EXPECT_EQ(status, 2);
    EXPECT_EQ(log, "");
}

TEST_F(FarmScriptTest, AssemblyRunsAfterTheRenderJob) {
    EXPECT_EQ(SubmitAssembly("a.sbatch", "123"),
              (std::vector<std::string>{"sbatch", "--parsable", "--dependency=afterok:123",
                                        "--kill-on-invalid-dep=yes", "a.sbatch"}));
    EXPECT_EQ(SubmitAssembly("a.sbatch", ""),
              (std::vector<std::string>{"sbatch", "--parsable", "a.sbatch"}));
    int status = -1;
    const std::string log = RunElement(AssembleScript(job_, dir_ + "/bin/rtrt"), 0, 0, 0, &status);
    EXPECT_EQ(log, "farm\n--assemble\n" + job_.folder + "\n");
}

}  // namespace
}  // namespace rtrt
