#include "engine/core/child_process.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rtrt {
namespace {

TEST(ChildProcessTest, StatusAndOutput) {
    std::string output;
    EXPECT_EQ(RunProgram({"sh", "-c", "echo out; echo err >&2; exit 3"}, &output), 3);
    EXPECT_EQ(output, "out\n");
    EXPECT_EQ(RunProgram({"sh", "-c", "kill -9 $$"}), 128 + 9);
}

TEST(ChildProcessTest, EnvironmentIsSetOnTopOfOurs) {
    ChildOptions o;
    o.environment = {{"RTRT_CHILD_TEST", "a b"}, {"HOME", "/elsewhere"}};
    std::string output;
    RunProgram({"sh", "-c", "printf '%s|%s|%s' \"$RTRT_CHILD_TEST\" \"$HOME\" \"${PATH:+path}\""},
               &output, o);
    EXPECT_EQ(output, "a b|/elsewhere|path");
}

TEST(ChildProcessTest, InputReachesTheChild) {
    ChildOptions o;
    o.pipeStdin = o.pipeStdout = true;
    ChildProcess child({"cat"}, o);
    ASSERT_TRUE(child.Started());
    // cat echoes while we write and its output is read only at Wait: less than a page, which
    // every pipe holds.
    const std::string text(3000, 'x');
    EXPECT_TRUE(child.WriteInput(text.data(), text.size()));
    std::string output;
    EXPECT_EQ(child.Wait(&output), 0);
    EXPECT_EQ(output, text);
}

TEST(ChildProcessTest, WritingToAChildThatExitedFailsWithoutEndingUs) {
    ChildOptions o;
    o.pipeStdin = true;
    ChildProcess child({"true"}, o);
    ASSERT_TRUE(child.Started());
    const std::string text(1 << 20, 'x');
    bool ok = true;
    for (int i = 0; i < 8 && ok; ++i) ok = child.WriteInput(text.data(), text.size());
    EXPECT_FALSE(ok);  // EPIPE, where SIGPIPE would have ended the test
    EXPECT_EQ(child.Wait(), 0);
}

TEST(ChildProcessTest, MissingProgram) {
    ChildProcess child({"rtrt-no-such-program"});
    EXPECT_FALSE(child.Started());
    EXPECT_NE(child.Error(), "");
    EXPECT_EQ(child.Wait(), 127);
    EXPECT_FALSE(ProgramOnPath("rtrt-no-such-program"));
    EXPECT_TRUE(ProgramOnPath("sh"));
    EXPECT_TRUE(ProgramOnPath("/bin/sh"));
}

}  // namespace
}  // namespace rtrt
