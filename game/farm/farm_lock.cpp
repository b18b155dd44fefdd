#include "game/farm/farm_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
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
    return text;
}

}  // namespace

FarmFolderLock::FarmFolderLock(const std::string& folder, int waitSeconds) : folder_(folder) {
    made_ = FirstMissing(folder);
    CreateOutputFolder(folder);
    const std::string path = folder + "/" + kFarmLockName;
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) {
        const int error = errno;
        Release();
        const std::string reason =
            "cannot open its lock file: " + std::string(std::strerror(error));
        if (error == EACCES || error == EROFS || error == ENOTDIR || error == ELOOP)
            throw InputError(folder, "", reason);
        throw OutputError(folder, reason);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(waitSeconds);
    while (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        if (error == EINTR) continue;
        if (error != EWOULDBLOCK) {  // e.g. ENOLCK: an NFS mount without its lock service
            Release();
            throw OutputError(
                folder, "cannot lock the job's folder (" + path + "): " + std::strerror(error));
        }
        if (std::chrono::steady_clock::now() < deadline) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            continue;
        }
        const std::string holder = Holder(fd_);
        Release();
        // Busy, not bad input: the same command succeeds once the other run has ended.
        throw OutputError(folder, "another rtrt farm" +
                                      (holder.empty() ? "" : " (" + holder + ")") +
                                      " is working in this folder; run this again once it has "
                                      "ended (rtrt farm --status shows the frames done), or "
                                      "give another -o");
    }
    char host[256] = "";
    ::gethostname(host, sizeof(host) - 1);
    const std::string holder =
        "process " + std::to_string(::getpid()) + " on " + std::string(host) + "\n";
    if (::ftruncate(fd_, 0) == 0) (void)!::pwrite(fd_, holder.data(), holder.size(), 0);
}

void FarmFolderLock::Release() {
    std::error_code ec;
    if (!made_.empty()) fs::remove_all(made_, ec);  // before the lock is let go
    made_.clear();
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
