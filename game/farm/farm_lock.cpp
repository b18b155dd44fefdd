#include "game/farm/farm_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <thread>

#include "engine/core/error.h"
#include "engine/core/output_file.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

// The first folder on the way to FOLDER that does not exist yet ("" when FOLDER exists): what a
// failed start removes again.
std::string FirstMissing(const std::string& folder) {
    std::error_code ec;
    fs::path missing;
    for (fs::path p = fs::absolute(folder, ec).lexically_normal(); !p.empty();
         p = p.parent_path()) {
        if (fs::exists(p, ec)) break;
        missing = p;
        if (p == p.parent_path()) break;
    }
    return missing.string();
}

// The process that holds the lock, as it wrote itself into the lock file.
std::string Holder(int fd) {
    char text[128] = "";
    const ssize_t n = ::pread(fd, text, sizeof(text) - 1, 0);
    text[n > 0 ? n : 0] = '\0';
    if (char* end = std::strchr(text, '\n')) *end = '\0';
    return WithoutControlCharacters(text);
}

// Opens PATH, creating it where missing: its descriptor (*created: this call made the file), or
// -1 with errno set.
int OpenOrCreate(const std::string& path, bool* created) {
    for (;;) {
        int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0644);
        *created = fd >= 0;
        if (fd >= 0 || errno != EEXIST) return fd;
        // O_NONBLOCK: a FIFO or a device in the file's place must not hold the open up.
        fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
        if (fd >= 0 || errno != ENOENT) return fd;  // ENOENT: its maker removed it meanwhile
    }
}

// What stands where the lock file should be, when it is not a regular file.
std::string KindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISLNK(mode)) return "a symbolic link";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISSOCK(mode)) return "a socket";
    return "a device";
}

}  // namespace

std::optional<std::string> FarmFolderHolder(const std::string& folder) {
    const std::string path = folder + "/" + kFarmLockName;
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0) return std::nullopt;
    std::optional<std::string> holder;
    if (::flock(fd, LOCK_SH | LOCK_NB) == 0)
        ::flock(fd, LOCK_UN);
    else if (errno == EWOULDBLOCK)
        holder = Holder(fd);
    ::close(fd);
    return holder;
}

FarmFolderLock::FarmFolderLock(const std::string& folder, int waitSeconds)
    : folder_(folder), path_(folder + "/" + kFarmLockName) {
    made_ = FirstMissing(folder);
    CreateOutputFolder(folder);
    bool created = OpenLockFile();
    // Half a second at least: rtrt farm --status takes the lock shared for an instant
    // (FarmFolderHolder), and a run starting then must not be refused for it.
    const auto deadline = std::chrono::steady_clock::now() +
                          std::max<std::chrono::milliseconds>(std::chrono::milliseconds(500),
                                                              std::chrono::seconds(waitSeconds));
    int replaced = 0;
    bool toldOfWait = false;
    for (;;) {
        if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) {
            if (LockedFileIsCurrent()) break;
            // The file was replaced under the lock: the run that held it has just left and removed
            // it. The one in its place is tried at once, a bounded number of times (a file system
            // whose fstat and lstat disagree would loop).
            ::close(fd_);
            fd_ = -1;
            created = OpenLockFile();
            if (++replaced < 8) continue;
            // Other runs work here: the folder stays; a file this run made just now is no one's.
            made_.clear();
            madeLockFile_ = created;
            Release();
            throw OutputError(folder,
                              "its lock file (" + path_ + ") keeps being replaced; run this again");
        }
        const int error = errno;
        if (error == EINTR) continue;
        if (error != EWOULDBLOCK) {   // e.g. ENOLCK: an NFS mount without its lock service
            madeLockFile_ = created;  // no run can hold a lock here: a file this run made goes
            Release();
            throw OutputError(
                folder, "cannot lock the job's folder (" + path_ + "): " + std::strerror(error));
        }
        if (std::chrono::steady_clock::now() < deadline) {
            // A wait of minutes (--assemble's) says what it waits for, once: it looked hung.
            if (waitSeconds > 1 && !toldOfWait) {
                const std::string holder = Holder(fd_);
                std::printf("rtrt farm: waiting up to %d s for another rtrt farm%s to leave %s\n",
                            waitSeconds, holder.empty() ? "" : (" (" + holder + ")").c_str(),
                            folder.c_str());
                std::fflush(stdout);
                toldOfWait = true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            continue;
        }
        const std::string holder = Holder(fd_);
        // Another run holds the lock: the folder this one made is that run's now, lock file and
        // all, and stays.
        made_.clear();
        Release();
        // Busy, not bad input: the same command succeeds once the other run has ended.
        throw OutputError(folder, "another rtrt farm" +
                                      (holder.empty() ? "" : " (" + holder + ")") +
                                      " is working in this folder; run this again once it has "
                                      "ended (rtrt farm --status shows the frames done), or "
                                      "give another -o");
    }
    // Only once it is held: a file made here but locked by another run is that run's to keep.
    madeLockFile_ = created;
    char host[256] = "";
    ::gethostname(host, sizeof(host) - 1);
    const std::string holder =
        "process " + std::to_string(::getpid()) + " on " + std::string(host) + "\n";
    if (::ftruncate(fd_, 0) == 0) (void)!::pwrite(fd_, holder.data(), holder.size(), 0);
}

bool FarmFolderLock::OpenLockFile() {
    bool created = false;
    fd_ = OpenOrCreate(path_, &created);
    const int error = errno;
    // A folder, a link or a FIFO in its place is the folder's state, not a failure: exit 2,
    // saying what to remove.
    struct stat info {};
    const bool opened = fd_ >= 0;
    // Whatever the open's error (EISDIR, ELOOP, ENXIO for a socket...), what stands there says
    // more.
    const bool known = opened ? ::fstat(fd_, &info) == 0 : ::lstat(path_.c_str(), &info) == 0;
    if (known && !S_ISREG(info.st_mode)) {
        Release();
        throw InputError(path_, "",
                         "is " + KindOf(info.st_mode) +
                             " where rtrt farm keeps its lock file; remove it and run this again");
    }
    if (!opened) {
        Release();
        const std::string reason =
            "cannot open its lock file: " + std::string(std::strerror(error));
        if (error == EACCES || error == EROFS || error == ENOTDIR || error == ELOOP)
            throw InputError(folder_, "", reason);
        throw OutputError(folder_, reason);
    }
    return created;
}

bool FarmFolderLock::LockedFileIsCurrent() const {
    struct stat locked;
    struct stat named;
    return ::fstat(fd_, &locked) == 0 && ::lstat(path_.c_str(), &named) == 0 &&
           locked.st_dev == named.st_dev && locked.st_ino == named.st_ino;
}

void FarmFolderLock::Release() {
    // Before the lock is let go; a run that was waiting for it then finds the file gone
    // (LockedFileIsCurrent) and locks the one in its place.
    std::error_code ec;
    if (!made_.empty()) {
        // The job's folder goes with what this run put into it; the folders above it that this
        // run made go only while empty: another job's folder may have been made in one since (a
        // slow sbatch that then refused had taken a sibling job's finished frames with it).
        fs::path folder = fs::absolute(folder_, ec).lexically_normal();
        if (folder.filename().empty()) folder = folder.parent_path();
        fs::remove_all(folder, ec);
        for (fs::path above = folder.parent_path(); above.string().size() >= made_.size();
             above = above.parent_path())
            if (!fs::remove(above, ec)) break;  // not empty: someone else's now
    } else if (madeLockFile_)
        ::unlink(path_.c_str());
    made_.clear();
    madeLockFile_ = false;
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

int FarmFolderLock::RemoveStaleTemporaries() const {
    int removed = 0;
    for (const std::string& dir : {folder_, folder_ + "/frames", folder_ + "/slurm"}) {
        std::error_code ec;
        for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
            const std::optional<long> owner = TemporaryOwnerHere(entry.path().filename().string());
            if (!owner || ::kill(pid_t(*owner), 0) == 0 || errno != ESRCH) continue;
            std::error_code ignored;
            if (fs::remove(entry.path(), ignored)) ++removed;
        }
    }
    return removed;
}

FarmFolderLock::~FarmFolderLock() { Release(); }

}  // namespace rtrt
