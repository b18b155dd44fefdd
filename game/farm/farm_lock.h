#pragma once
// One `rtrt farm` at a time in a job's folder: two runs that start the same (or a new) folder
// together would each write farm.json and render into the other's frames, and two submissions
// would each rewrite the list of Slurm jobs and lose one.
#include <string>

namespace rtrt {

// The lock file's name in a job's folder.
inline constexpr const char* kFarmLockName = ".rtrt-farm.lock";

class FarmFolderLock {
  public:
    // Creates folder if it is missing and takes its lock (an flock on FOLDER/.rtrt-farm.lock,
    // released when this object goes or the process ends, however it ends). InputError(folder,
    // "", reason) when another process holds it, naming that process. A folder this call made
    // is removed again if the lock is released before Keep().
    explicit FarmFolderLock(const std::string& folder);
    FarmFolderLock(const FarmFolderLock&) = delete;
    FarmFolderLock& operator=(const FarmFolderLock&) = delete;
    ~FarmFolderLock();

    // The work has started: the folder stays, whatever happens next.
    void Keep() { madeFolder_ = false; }

  private:
    std::string folder_;
    int fd_ = -1;
    bool madeFolder_ = false;
};

}  // namespace rtrt
