// Scripted window input: malformed scripts name the line and the reason; events reach Input over
// the frames they span, as GLFW's callbacks would deliver them.
#include "game/app/input_script.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "engine/core/error.h"
#include "game/app/controls.h"

namespace rtrt {
namespace {

// ctest runs each test in its own process, several at once: the process id keeps their files
// apart (a shared counter alone gave every process rtrt_script_0.txt, and tests read each
// other's scripts).
std::string Write(const std::string& text) {
    static int count = 0;
    const std::string name =
        "rtrt_script_" + std::to_string(getpid()) + "_" + std::to_string(count++) + ".txt";
    const std::string path = (std::filesystem::temp_directory_path() / name).string();
    std::ofstream(path) << text;
    return path;
}

void ExpectError(const std::string& text, const std::string& field, const std::string& reason) {
    try {
        InputScript::Load(Write(text));
        FAIL() << "no error for: " << text;
    } catch (const InputError& e) {
        EXPECT_EQ(e.Field(), field);
        EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
}

TEST(InputScript, MalformedLinesNameTheLineAndReason) {
    ExpectError("1 key 1\n\n3 jump\n", "line 3", "unknown command \"jump\"");
    ExpectError("1 key Hyper\n", "line 1", "unknown key \"Hyper\"");
    ExpectError("# comment\n2 click 10\n", "line 2", "click needs 2 numbers");
    ExpectError("2 quit now\n", "line 1", "unexpected \"now\"");
    ExpectError("-1 quit\n", "line 1", "frame must be >= 0");
    ExpectError("2147483647 quit\n", "line 1", "at most 100000000");
    ExpectError("key 1\n", "line 1", "expected FRAME COMMAND ARGS");
    // The frame is the whole first word: "1.5" was read as frame 1 and command ".5".
    ExpectError("1.5 quit\n", "line 1", "FRAME a whole number, got \"1.5\"");
    ExpectError("99999999999999999999 quit\n", "line 1", "at most 100000000");
    ExpectError("-99999999999999999999 quit\n", "line 1", "frame must be >= 0");
    // Screenshot paths are checked when the script is read, not when their frame comes.
    ExpectError("1 quit\n2 screenshot /nonexistent-rtrt-folder/shot.png\n", "line 2",
                "screenshot /nonexistent-rtrt-folder/shot.png: ");
    ExpectError("3 screenshot shot.unknown-format\n", "line 1", "screenshot shot.unknown-format");
    // Found by probing: 1e38 pixels overflowed the mouse to inf and the camera to NaN; "nan" was
    // "needs 2 numbers"; a five-million-letter key name was quoted whole.
    ExpectError("0 look 3e38 3e38\n", "line 1", "look: expected a number of pixels within 1e6");
    ExpectError("0 click nan 1\n", "line 1",
                "click: expected a number of pixels within 1e6, got \"nan\"");
    try {
        InputScript::Load(Write("0 key " + std::string(100000, 'A') + "\n"));
        FAIL() << "no error for a long key name";
    } catch (const InputError& e) {
        EXPECT_LT(std::string(e.what()).size(), 300u);
    }
}

// A screenshot over the script itself, or where --record DIR will write a frame, is refused when
// the script is read: the script had been replaced by the image, the screenshot by the frame.
TEST(InputScript, ScreenshotsOverTheScriptOrARecordedFrameAreRefused) {
    const std::string script = Write("");
    std::ofstream(script) << "0 screenshot " << script << "\n";
    EXPECT_THROW(InputScript::Load(script), InputError);
    const std::string folder =
        (std::filesystem::temp_directory_path() / ("rtrt_frames_" + std::to_string(getpid())))
            .string();
    const std::string frame = Write("0 screenshot " + folder + "/frame_00000.png\n");
    try {
        InputScript::Load(frame, folder);
        FAIL() << "no error for a screenshot named like a recorded frame";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("written over by a frame of --record"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(InputScript::Load(Write("0 screenshot " + folder + "/frame_123456.png\n"), folder),
                 InputError);  // past frame 99999 the names grow a digit
    EXPECT_NO_THROW(InputScript::Load(Write("0 screenshot " + folder + "/shot.png\n"), folder));
    EXPECT_NO_THROW(InputScript::Load(Write("0 screenshot " + folder + "/frame_1.png\n"), folder));
}

// Events act in frame order whatever the order of their lines: a key pressed again on the frame
// its first press is released was dropped when its line came first.
TEST(InputScript, EventsActInFrameOrder) {
    InputScript script = InputScript::Load(Write("1 key 1\n0 key 1\n"));
    Input in;
    int presses = 0;
    for (int frame = 0; frame < 4; ++frame) {
        in.BeginFrame();
        script.Apply(frame, in);
        presses += in.Pressed(KeyByName("1"));
    }
    EXPECT_EQ(presses, 2);
}

// play --record DIR makes DIR once the window opens: screenshots into it are checked for their
// format only while it is missing (the load-time check refused them).
TEST(InputScript, ScreenshotsIntoTheRecordFolderWaitForIt) {
    const std::string folder =
        (std::filesystem::temp_directory_path() / ("rtrt_pending_" + std::to_string(getpid())))
            .string();
    const std::string script = Write("1 screenshot " + folder + "/shot.ppm\n");
    EXPECT_THROW(InputScript::Load(script), InputError);
    EXPECT_NO_THROW(InputScript::Load(script, folder));
    EXPECT_NO_THROW(InputScript::Load(script, folder + "/"));
    EXPECT_THROW(
        InputScript::Load(Write("1 screenshot " + folder + "/shot.unknown-format\n"), folder),
        InputError);
    EXPECT_THROW(InputScript::Load(script, folder + "-other"), InputError);
}

TEST(InputScript, AByteOrderMarkBeforeTheFirstLineIsIgnored) {
    InputScript script =
        InputScript::Load(Write("\xEF\xBB\xBF"
                                "4 quit\n"));
    EXPECT_EQ(script.LastFrame(), 6);
}

// A FIFO is refused at once (reading it would wait for a writer), as a device or a folder is.
TEST(InputScript, OnlyRegularFilesAreRead) {
    const std::string fifo =
        (std::filesystem::temp_directory_path() / ("rtrt_script_fifo_" + std::to_string(getpid())))
            .string();
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_THROW(InputScript::Load(fifo), InputError);
    std::filesystem::remove(fifo);
    EXPECT_THROW(InputScript::Load("/dev/zero"), InputError);
    EXPECT_THROW(InputScript::Load(std::filesystem::temp_directory_path().string()), InputError);
}

TEST(InputScript, DragSpansThreeFramesAndKeysRelease) {
    InputScript script =
        InputScript::Load(Write("1 drag 10 20 50 20 # comment\n1 key F5\n"
                                "4 screenshot shot.png\n5 quit\n"));
    EXPECT_EQ(script.LastFrame(), 7);
    Input in;
    in.BeginFrame();
    script.Apply(0, in);
    EXPECT_FALSE(in.leftDown);
    in.BeginFrame();
    script.Apply(1, in);
    EXPECT_TRUE(in.leftPressed && in.leftDown);
    EXPECT_EQ(in.mouse, vec2(10, 20));
    EXPECT_TRUE(in.Pressed(KeyByName("F5")));
    in.BeginFrame();
    script.Apply(2, in);
    EXPECT_EQ(in.mouseDelta, vec2(40, 0));
    EXPECT_TRUE(in.leftDown && !in.leftPressed);
    EXPECT_FALSE(in.down[KeyByName("F5")]);
    in.BeginFrame();
    script.Apply(3, in);
    EXPECT_TRUE(in.leftReleased && !in.leftDown);
    in.BeginFrame();
    const InputScript::Effects shot = script.Apply(4, in);
    ASSERT_EQ(shot.screenshots.size(), 1u);
    EXPECT_EQ(shot.screenshots[0], "shot.png");
    EXPECT_TRUE(script.Apply(5, in).quit);
}

}  // namespace
}  // namespace rtrt
