// Where whole files may be written: checked paths, and targets that a rename must not replace.
#include "engine/core/output_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

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
    // A file where a folder of the path should be had been reported as a missing folder.
    EXPECT_EQ(Reason((dir_ / "old.json" / "r.json").string()),
              (dir_ / "old.json").string() + " is a file, not a folder");
    EXPECT_EQ(Reason((dir_ / "old.json" / "sub" / "r.json").string()),
              (dir_ / "old.json").string() + " is a file, not a folder");
    EXPECT_EQ(Reason(fifo_), "is not a regular file (a device, FIFO or socket)");
    EXPECT_EQ(Reason("/dev/null"), "is not a regular file (a device, FIFO or socket)");
    // A name the file system cannot hold failed only at the rename, after the work.
    EXPECT_EQ(Reason((dir_ / (std::string(251, 'a') + ".json")).string()),
              "the file name is too long (256 bytes; file systems take at most 255)");
    EXPECT_EQ(Reason((dir_ / (std::string(250, 'a') + ".json")).string()), "");
}

// A folder that lets this process write but takes no new file (/proc as root: access() passes)
// is refused up front, and the check leaves nothing behind where it passes.
TEST_F(OutputPathTest, AFolderThatTakesNoNewFilesIsRefusedUpFront) {
    const std::string reason = Reason("/proc/frame.png");
    if (::geteuid() == 0)
        EXPECT_EQ(reason, "cannot write into the folder /proc: it takes no new files");
    else
        EXPECT_EQ(reason.rfind("cannot write into the folder /proc: ", 0), 0u) << reason;
    EXPECT_EQ(Reason((dir_ / "new.png").string()), "");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
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

// Whether text is well-formed UTF-8 (each lead byte followed by as many continuation bytes as it
// announces).
bool IsUtf8(const std::string& text) {
    for (size_t k = 0; k < text.size();) {
        const auto lead = static_cast<unsigned char>(text[k]);
        const size_t length = lead < 0x80           ? 1
                              : (lead >> 5) == 0x6  ? 2
                              : (lead >> 4) == 0xe  ? 3
                              : (lead >> 3) == 0x1e ? 4
                                                    : 0;
        if (length == 0 || k + length > text.size()) return false;
        for (size_t c = 1; c < length; ++c)
            if ((static_cast<unsigned char>(text[k + c]) & 0xc0) != 0x80) return false;
        k += length;
    }
    return true;
}

// A target whose name is near the file system's limit (255 bytes) is still written: the
// temporary beside it gets a shortened name that keeps to the limit, cut between characters.
TEST_F(OutputPathTest, NamesNearTheLengthLimitAreWritten) {
    std::vector<std::string> names = {std::string(250, 'a') + ".png", std::string(255, 'b')};
    // Two-byte characters (U+00E9) after 0 or 1 ASCII bytes: whatever this host's name and
    // process id make the cut, it falls inside a character for one of the two.
    for (int ascii = 0; ascii < 2; ++ascii) {
        std::string name(size_t(ascii), 'a');
        while (name.size() + 2 <= 250) name += "\xc3\xa9";
        names.push_back(name + ".json");
    }
    for (const std::string& name : names) {
        ASSERT_LE(name.size(), 255u);
        const fs::path target = dir_ / name;
        const std::string temporary = TemporaryPathFor(target.string());
        const std::string temporaryName = fs::path(temporary).filename().string();
        EXPECT_LE(temporaryName.size(), 255u) << temporaryName;
        EXPECT_EQ(fs::path(temporary).parent_path(), dir_);
        EXPECT_NE(temporaryName, name);
        EXPECT_TRUE(IsUtf8(temporaryName)) << temporaryName;
        WriteWholeFile(target.string(), "{}\n", false);
        EXPECT_TRUE(fs::is_regular_file(target)) << target;
        EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}), 2)
            << "the target and the FIFO, no temporary left";
        fs::remove(target);
    }
    // Two long names that differ only past the cut get different temporaries.
    EXPECT_NE(TemporaryPathFor((dir_ / (std::string(250, 'c') + "1")).string()),
              TemporaryPathFor((dir_ / (std::string(250, 'c') + "2")).string()));
}

// A temporary's name says which process of this host made it, so that one left by a killed
// process can be found; other names, and other hosts' temporaries, are no one's here.
TEST_F(OutputPathTest, TemporariesNameTheirProcess) {
    for (const std::string& target : {(dir_ / "frame_0001.png").string(), (dir_ / "noext").string(),
                                      (dir_ / (std::string(250, 'a') + ".json")).string()}) {
        const std::string name = fs::path(TemporaryPathFor(target)).filename().string();
        EXPECT_EQ(TemporaryOwnerHere(name), std::optional<long>(::getpid())) << name;
    }
    const std::string mine = fs::path(TemporaryPathFor("x.png")).filename().string();
    const std::string host = mine.substr(mine.find('-') + 1, mine.rfind('.') - mine.find('-') - 1);
    EXPECT_EQ(TemporaryOwnerHere(".x.partial17-" + host + ".png"), std::optional<long>(17));
    for (const std::string& other :
         {std::string("x.png"), std::string(".x.partial-" + host + ".png"),
          std::string(".x.partial17-" + host + "x.png"), std::string(".x.partial17.png"),
          std::string(".x.partial17-" + host + ".png.bak"), std::string(".partial17-" + host)})
        EXPECT_EQ(TemporaryOwnerHere(other), std::nullopt) << other;
}

// Another host's temporary is still a temporary (a farm's job folder holds those of every
// machine), with its host and process told; names that only look alike are none.
TEST(TemporaryNameTest, ParsesTheProcessAndHostOfAnyHost) {
    const std::optional<TemporaryName> other = ParseTemporaryName(".farm.partial4242-node-07.json");
    ASSERT_TRUE(other);
    EXPECT_EQ(other->pid, 4242);
    EXPECT_EQ(other->host, "node-07");
    const std::optional<TemporaryName> bare = ParseTemporaryName(".check.partial9");
    ASSERT_TRUE(bare);
    EXPECT_EQ(bare->pid, 9);
    EXPECT_EQ(bare->host, "");
    ASSERT_TRUE(ParseTemporaryName(".a.b.partial12-h.png"));
    EXPECT_EQ(ParseTemporaryName(".a.b.partial12-h.png")->host, "h");
    for (const std::string& none :
         {std::string("farm.partial1-h.json"), std::string(".farm.partial-h.json"),
          std::string(".farm.partial1-.json"), std::string(".farm.partial1-h_x.json"),
          std::string(".farm.partial1x.json"), std::string(".farm.partial1-h.json.bak"),
          std::string(".partial1-h"), std::string(".farm.partial0-h"),
          std::string(".farm.partial99999999999-h")})
        EXPECT_EQ(ParseTemporaryName(none), std::nullopt) << none;
}

std::string ReadAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// An output named by a link is written where the link leads, as a shell's > writes, and the link
// stays: replacing it had turned a link to a shared file into a private copy, and as root had
// put a regular file in place of /dev/stdout.
TEST_F(OutputPathTest, AnOutputNamedByALinkIsWrittenThroughIt) {
    fs::create_directories(dir_ / "real");
    WriteWholeFile((dir_ / "real" / "report.json").string(), "old\n", false);
    fs::create_symlink("real/report.json", dir_ / "link.json");
    fs::create_symlink("link.json", dir_ / "link2.json");  // a link to a link
    EXPECT_EQ(Reason((dir_ / "link2.json").string()), "");
    WriteWholeFile((dir_ / "link2.json").string(), "new\n", false);
    EXPECT_TRUE(fs::is_symlink(dir_ / "link.json"));
    EXPECT_TRUE(fs::is_symlink(dir_ / "link2.json"));
    EXPECT_EQ(ReadAll(dir_ / "real" / "report.json"), "new\n");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "real"), fs::directory_iterator()), 1);
    // A dangling link makes the file it names; a loop and a link to a device are refused.
    fs::create_symlink("real/made.json", dir_ / "dangling.json");
    WriteWholeFile((dir_ / "dangling.json").string(), "made\n", false);
    EXPECT_EQ(ReadAll(dir_ / "real" / "made.json"), "made\n");
    fs::create_symlink("loop_b", dir_ / "loop_a");
    fs::create_symlink("loop_a", dir_ / "loop_b");
    EXPECT_EQ(Reason((dir_ / "loop_a").string()), "is a loop of links");
    // A link to an open descriptor (/dev/stdout's /proc/self/fd/1) is no file to write beside:
    // renamed over, a file the shell opened for >> lost what it held.
    // However the way there is spelled: relative, doubled slashes, through /dev/fd.
    std::string relative;
    for (auto part = ++dir_.begin(); part != dir_.end(); ++part) relative += "../";
    for (const std::string& target : {std::string("/dev/fd/1"), std::string("//proc/self/fd/1"),
                                      std::string("/dev//fd/1"), relative + "proc/self/fd/1"}) {
        fs::remove(dir_ / "stdout.json");
        fs::create_symlink(target, dir_ / "stdout.json");
        EXPECT_NE(Reason((dir_ / "stdout.json").string())
                      .find(", an open descriptor (as "
                            "/dev/stdout does)"),
                  std::string::npos)
            << target;
        EXPECT_THROW(WriteWholeFile((dir_ / "stdout.json").string(), "x", false), InputError);
        EXPECT_TRUE(fs::is_symlink(dir_ / "stdout.json"));
    }
    // A link of one's own reached through /proc (a process's cwd or root) is an ordinary link.
    fs::create_symlink("real/report.json", dir_ / "own.json");
    const std::string viaProc = "/proc/self/root" + (dir_ / "own.json").string();
    EXPECT_EQ(Reason(viaProc), "");
    WriteWholeFile(viaProc, "via proc\n", false);
    EXPECT_EQ(ReadAll(dir_ / "real" / "report.json"), "via proc\n");
    fs::create_symlink("/dev/null", dir_ / "null.json");
    EXPECT_EQ(Reason((dir_ / "null.json").string()),
              "is not a regular file (a device, FIFO or socket) (where the link leads: /dev/null)");
    EXPECT_THROW(WriteWholeFile((dir_ / "null.json").string(), "x", false), InputError);
    EXPECT_TRUE(fs::is_symlink(dir_ / "null.json"));
}

// One file under other names (a link, a hard link, another spelling) is one file; two new paths
// are one where they resolve alike.
TEST_F(OutputPathTest, NameTheSameFileSeesThroughSpellingsAndLinks) {
    const fs::path scene = dir_ / "scene.json";
    WriteWholeFile(scene.string(), "{}", false);
    fs::create_symlink("scene.json", dir_ / "link.json");
    fs::create_hard_link(scene, dir_ / "hard.json");
    fs::create_directories(dir_ / "sub");
    for (const fs::path& alias : {dir_ / "link.json", dir_ / "hard.json",
                                  dir_ / "sub" / ".." / "scene.json", dir_ / "." / "scene.json"})
        EXPECT_TRUE(NameTheSameFile(scene.string(), alias.string())) << alias;
    EXPECT_TRUE(NameTheSameFile((dir_ / "new.csv").string(), (dir_ / "sub/../new.csv").string()));
    EXPECT_FALSE(NameTheSameFile(scene.string(), (dir_ / "other.json").string()));
    EXPECT_FALSE(NameTheSameFile((dir_ / "a.csv").string(), (dir_ / "b.csv").string()));
}

// A write-protected file is not replaced (the rename into place needed only the folder, and the
// file became the writer's). Root may write anything: the check runs as another user there.
TEST_F(OutputPathTest, AWriteProtectedFileIsRefused) {
    const fs::path target = dir_ / "protected.png";
    WriteWholeFile(target.string(), "old", false);
    ASSERT_EQ(::chmod(target.c_str(), 0444), 0);
    ASSERT_EQ(::chmod(dir_.c_str(), 0777), 0);
    const auto refused = [&] {
        try {
            CheckOutputPath(target.string());
        } catch (const InputError& e) {
            return std::string(e.Reason()).find("is write-protected") != std::string::npos;
        }
        return false;
    };
    if (::geteuid() != 0) {
        EXPECT_TRUE(refused());
    } else {
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) _exit(::setgid(65534) == 0 && ::setuid(65534) == 0 && refused() ? 0 : 1);
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
    EXPECT_EQ(ReadAll(target), "old");
}

// A file replaced keeps its permissions (a private file stays private) and, as root, its owner.
TEST_F(OutputPathTest, AReplacedFileKeepsItsModeAndOwner) {
    const fs::path target = dir_ / "private.png";
    WriteWholeFile(target.string(), "old", false);
    ASSERT_EQ(::chmod(target.c_str(), 0600), 0);
    const bool root = ::geteuid() == 0;
    if (root) {
        ASSERT_EQ(::chown(target.c_str(), 65534, 65534), 0);
    }
    WriteWholeFile(target.string(), "new", false);
    struct stat st {};
    ASSERT_EQ(::stat(target.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0600u);
    if (root) {
        EXPECT_EQ(st.st_uid, 65534u);
    }
    EXPECT_EQ(ReadAll(target), "new");
}

}  // namespace
}  // namespace rtrt
