// The lock of a job's folder: a refused run leaves the folder as it found it, a bad lock file is
// the user's to remove (exit 2), and the holder's text is printed harmlessly.
#include "game/farm/farm_lock.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <set>
#include <string>
#include <thread>

#include "engine/core/error.h"

namespace rtrt {
namespace {
namespace fs = std::filesystem;

class FarmLockTest : public testing::Test {
  protected:
    void SetUp() override {
        folder_ =
            (fs::temp_directory_path() / ("rtrt_farm_lock_test_" + std::to_string(::getpid())))
                .string();
        fs::remove_all(folder_);
        fs::create_directories(folder_);
        lockFile_ = folder_ + "/" + kFarmLockName;
    }
    void TearDown() override { fs::remove_all(folder_); }

    std::set<std::string> Names() const {
        std::set<std::string> names;
        for (const fs::directory_entry& entry : fs::directory_iterator(folder_))
            names.insert(entry.path().filename().string());
        return names;
    }

    std::string folder_, lockFile_;
};

TEST_F(FarmLockTest, ReleasedBeforeKeepLeavesTheFolderAsFound) {
    std::ofstream(folder_ + "/notes.txt") << "x\n";
    { FarmFolderLock lock(folder_); }
    EXPECT_EQ(Names(), (std::set<std::string>{"notes.txt"}));
    {
        FarmFolderLock lock(folder_);
        lock.Keep();
    }
    EXPECT_EQ(Names(), (std::set<std::string>{"notes.txt", kFarmLockName}));
    { FarmFolderLock lock(folder_); }  // a lock file that was there before stays
    EXPECT_EQ(Names(), (std::set<std::string>{"notes.txt", kFarmLockName}));
}

TEST_F(FarmLockTest, NewFoldersGoWhenNothingIsKept) {
    { FarmFolderLock lock(folder_ + "/a/job"); }
    EXPECT_TRUE(Names().empty());
}

// A run that made a/ for its job a/one and was refused (sbatch said no) after another run had
// made a/two beside it takes its own folder back, not a/ with the other job in it.
TEST_F(FarmLockTest, RefusedRunKeepsAFolderAnotherJobWroteIntoSince) {
    {
        FarmFolderLock first(folder_ + "/a/one");
        {
            FarmFolderLock second(folder_ + "/a/two");
            second.Keep();
        }
        std::ofstream(folder_ + "/a/two/frame_000000.png") << "frame\n";
        std::ofstream(folder_ + "/a/one/farm.json") << "{}\n";
    }
    EXPECT_FALSE(fs::exists(folder_ + "/a/one"));
    EXPECT_TRUE(fs::exists(folder_ + "/a/two/frame_000000.png"));
    EXPECT_EQ(Names(), (std::set<std::string>{"a"}));
}

TEST_F(FarmLockTest, LockFileThatIsAFolderIsBadInputSayingWhatToDo) {
    fs::create_directory(lockFile_);
    try {
        FarmFolderLock lock(folder_);
        ADD_FAILURE() << "took a lock whose file is a folder";
    } catch (const InputError& e) {
        EXPECT_EQ(e.File(), lockFile_);
        EXPECT_NE(e.Reason().find("is a folder"), std::string::npos) << e.what();
        EXPECT_NE(e.Reason().find("remove it"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_directory(lockFile_));
}

TEST_F(FarmLockTest, LockFileThatIsASymbolicLinkIsBadInput) {
    fs::create_symlink(folder_ + "/elsewhere", lockFile_);
    try {
        FarmFolderLock lock(folder_);
        ADD_FAILURE() << "took a lock whose file is a symbolic link";
    } catch (const InputError& e) {
        EXPECT_NE(e.Reason().find("is a symbolic link"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(folder_ + "/elsewhere"));
}

// A socket there fails the open with ENXIO, which named no kind before: exit 1 with the raw errno.
TEST_F(FarmLockTest, LockFileThatIsASocketIsBadInput) {
    const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_GE(s, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    ASSERT_LT(lockFile_.size(), sizeof(address.sun_path));
    std::strcpy(address.sun_path, lockFile_.c_str());
    ASSERT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
    try {
        FarmFolderLock lock(folder_);
        ADD_FAILURE() << "took a lock whose file is a socket";
    } catch (const InputError& e) {
        EXPECT_NE(e.Reason().find("is a socket"), std::string::npos) << e.what();
    }
    ::close(s);
}

// The lock file is anyone's to write: its text reaches the terminal with control characters
// (an escape sequence here) written out, never sent.
TEST_F(FarmLockTest, HolderTextIsEscaped) {
    const int fd = ::open(lockFile_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    const std::string text = "process 7 on \x1b]0;owned\x07host\r\n";
    ASSERT_EQ(::write(fd, text.data(), text.size()), ssize_t(text.size()));
    try {
        FarmFolderLock lock(folder_);
        ADD_FAILURE() << "took a lock another holder has";
    } catch (const OutputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("(process 7 on \\x1b]0;owned\\x07host\\x0d)"), std::string::npos)
            << message;
        EXPECT_EQ(message.find('\x1b'), std::string::npos);
        EXPECT_EQ(message.find('\x07'), std::string::npos);
    }
    ::close(fd);
}

// A run that waited while the holder removed the lock file it had made locks the file now in its
// place, so that a third run is refused instead of locking a file nobody else holds.
TEST_F(FarmLockTest, WaiterLocksTheFileInPlaceOfARemovedOne) {
    auto first = std::make_unique<FarmFolderLock>(folder_);
    std::promise<void> locked, checked;
    std::future<void> lockedFuture = locked.get_future(), checkedFuture = checked.get_future();
    std::thread waiter([&] {
        try {
            FarmFolderLock second(folder_, /*waitSeconds=*/30);
            locked.set_value();
            checkedFuture.wait();
        } catch (...) {
            locked.set_exception(std::current_exception());
        }
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the waiter has opened the file
    first.reset();  // released before Keep(): its lock file goes
    const bool secondLocked =
        lockedFuture.wait_for(std::chrono::seconds(20)) == std::future_status::ready;
    EXPECT_TRUE(secondLocked);
    if (secondLocked) {
        EXPECT_NO_THROW(lockedFuture.get());
        EXPECT_TRUE(fs::is_regular_file(lockFile_));
        EXPECT_THROW(FarmFolderLock third(folder_), OutputError);
    }
    checked.set_value();
    waiter.join();
}

}  // namespace
}  // namespace rtrt
