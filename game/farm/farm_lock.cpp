#include "game/farm/farm_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/core/output_file.h"

namespace rtrt {

FarmFolderLock::FarmFolderLock(const std::string& folder) : folder_(folder) {
    std::error_code ec;
    madeFolder_ = !std::filesystem::exists(folder, ec);
    CreateOutputFolder(folder);
    const std::string path = folder + "/" + kFarmLockName;
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) {
        const int error = errno;
        if (madeFolder_) std::filesystem::remove_all(folder_, ec);
        throw InputError(folder, "",
                         "cannot open its lock file: " + std::string(std::strerror(error)));
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        // The holder wrote its process id and host when it took the lock.
        char holder[128] = "";
        const ssize_t n = ::pread(fd_, holder, sizeof(holder) - 1, 0);
        holder[n > 0 ? n : 0] = '\0';
        if (char* end = std::strchr(holder, '\n')) *end = '\0';
        ::close(fd_);
        fd_ = -1;
        throw InputError(folder, "",
                         std::string("another rtrt farm") +
                             (holder[0] ? " (" + std::string(holder) + ")" : std::string()) +
                             " is working in this folder; wait until it ends (rtrt farm --status "
                             "shows the frames done), or give another -o");
    }
    char host[256] = "";
    ::gethostname(host, sizeof(host) - 1);
    const std::string holder =
        "process " + std::to_string(::getpid()) + " on " + std::string(host) + "\n";
    if (::ftruncate(fd_, 0) == 0) (void)!::pwrite(fd_, holder.data(), holder.size(), 0);
}

FarmFolderLock::~FarmFolderLock() {
    if (fd_ < 0) return;
    std::error_code ec;
    if (madeFolder_) std::filesystem::remove_all(folder_, ec);  // before the lock is let go
    ::close(fd_);
}

}  // namespace rtrt
