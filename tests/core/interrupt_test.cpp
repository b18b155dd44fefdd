// SIGINT and SIGTERM: the process exits 128 + the signal's number, the registered temporaries are
// gone and finished outputs stay. Each case runs in a death-test child that interrupts itself.
#include "engine/core/interrupt.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "engine/core/output_file.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

fs::path FreshFolder(const std::string& name) {
    fs::path folder = fs::temp_directory_path() /
                      ("rtrt_interrupt_test_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

std::string Contents(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteWhole(const fs::path& target, const std::string& bytes) {
    OutputFile file(target.string());
    file.Write(bytes.data(), bytes.size());
    file.Finish(/*durable=*/false);
    file.Commit();
}

// Writes FINISHED whole, then interrupts itself with SIGNO in the middle of writing UNFINISHED.
[[noreturn]] void InterruptWhileWriting(const fs::path& folder, int signo) {
    InstallInterruptHandler();
    WriteWhole(folder / "finished", "whole");
    OutputFile unfinished((folder / "unfinished").string());
    unfinished.Write("half", 4);
    kill(getpid(), signo);
    for (;;) pause();  // the interrupt thread exits the process
}

TEST(InterruptTest, SigintExits130KeepsFinishedOutputsAndRemovesTemporaries) {
    const fs::path folder = FreshFolder("int");
    EXPECT_EXIT(InterruptWhileWriting(folder, SIGINT), ::testing::ExitedWithCode(130),
                "rtrt: interrupted \\(SIGINT\\)");
    EXPECT_EQ(Contents(folder / "finished"), "whole");
    EXPECT_FALSE(fs::exists(folder / "unfinished"));
    EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 1);
    fs::remove_all(folder);
}

TEST(InterruptTest, SigtermExits143) {
    const fs::path folder = FreshFolder("term");
    EXPECT_EXIT(InterruptWhileWriting(folder, SIGTERM), ::testing::ExitedWithCode(143),
                "rtrt: interrupted \\(SIGTERM\\)");
    EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 1);
    fs::remove_all(folder);
}

// A thread started before the handler (as log4cplus's pool is, by a static initialiser) does not
// block the signals: one sent to it must still end in the cleanup.
TEST(InterruptTest, SignalToAThreadStartedBeforeTheHandlerIsHandedOn) {
    const fs::path folder = FreshFolder("early");
    EXPECT_EXIT(
        {
            std::thread early([] {
                for (;;) pause();
            });
            InstallInterruptHandler();
            OutputFile unfinished((folder / "unfinished").string());
            // NOLINTNEXTLINE(bugprone-bad-signal-to-kill-thread): the test is that it is handed on
            pthread_kill(early.native_handle(), SIGTERM);
            for (;;) pause();
        },
        ::testing::ExitedWithCode(143), "rtrt: interrupted \\(SIGTERM\\)");
    EXPECT_TRUE(fs::is_empty(folder));  // the temporary is gone
    fs::remove_all(folder);
}

TEST(InterruptTest, RegisteredFolderGoesWithWhatItHolds) {
    const fs::path folder = FreshFolder("folder");
    const fs::path scratch = folder / "scratch";
    EXPECT_EXIT(
        {
            InstallInterruptHandler();
            {
                TemporariesLock lock;
                fs::create_directories(scratch / "inner");
                lock.Register(scratch.string());
            }
            std::ofstream(scratch / "inner" / "file") << "data";
            kill(getpid(), SIGTERM);
            for (;;) pause();
        },
        ::testing::ExitedWithCode(143), "");
    EXPECT_FALSE(fs::exists(scratch));
    fs::remove_all(folder);
}

TEST(InterruptTest, UnregisterTakesBackOneRegistration) {
    const fs::path folder = FreshFolder("kept");
    const fs::path kept = folder / "kept", shared = folder / "shared";
    EXPECT_EXIT(
        {
            InstallInterruptHandler();
            std::ofstream(kept) << "data";
            std::ofstream(shared) << "data";
            {
                TemporariesLock lock;
                lock.Register(kept.string());
                lock.Unregister(kept.string());
                lock.Register(shared.string());  // two writers of one temporary
                lock.Register(shared.string());
                lock.Unregister(shared.string());
            }
            kill(getpid(), SIGINT);
            for (;;) pause();
        },
        ::testing::ExitedWithCode(130), "");
    EXPECT_EQ(Contents(kept), "data");
    EXPECT_FALSE(fs::exists(shared));
    fs::remove_all(folder);
}

}  // namespace
}  // namespace rtrt
