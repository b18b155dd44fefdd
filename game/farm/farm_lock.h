#pragma once
// One `rtrt farm` at a time in a job's folder: two runs that start the same (or a new) folder
// together would each write farm.json and render into the other's frames, and two submissions
// would each rewrite the list of Slurm jobs and lose one.
#include <optional>
#include <string>

namespace rtrt {

// The lock file's name in a job's folder.
inline constexpr const char* kFarmLockName = ".rtrt-farm.lock";

// Who holds FOLDER's lock ("process N on HOST"; "" where it does not say), or nothing where no
// run holds it. Only reads, so that it works on a folder this user cannot write.
std::optional<std::string> FarmFolderHolder(const std::string& folder);

class FarmFolderLock {
  public:
    // Creates folder if it is missing and takes its lock (an flock on FOLDER/.rtrt-farm.lock,
    // released when this object goes or the process ends, however it ends), waiting up to
    // waitSeconds (half a second at least) for another holder to let go. OutputError (exit 1: run
    // it again later) when the lock stays held, naming its holder, or cannot be taken; InputError
    // for a folder that cannot be made or whose lock file is not a regular file. The folders and
    // the lock file this call made are removed again if the lock is released before Keep(), so that
    // a refused run leaves the folder as it found it.
    explicit FarmFolderLock(const std::string& folder, int waitSeconds = 0);
    FarmFolderLock(const FarmFolderLock&) = delete;
    FarmFolderLock& operator=(const FarmFolderLock&) = delete;
    ~FarmFolderLock();

    // The work has started: the folder stays, whatever happens next.
    void Keep() {
        made_.clear();
        madeLockFile_ = false;
    }
    // Removes the temporaries (TemporaryOwnerHere) that processes of this host left in the
    // folder, its frames and its batch scripts and that are gone (a task or an rtrt killed with
    // SIGKILL): only a holder of the lock may, since no rtrt farm of this host can be writing
    // them. Returns how many were removed.
    int RemoveStaleTemporaries() const;

  private:
    void Release();
    // Opens the lock file, creating it where missing (true: this call made it); InputError when
    // something else than a regular file has its name.
    bool OpenLockFile();
    // Whether the lock file's name still leads to the file fd_ locks: a run that let go of a lock
    // file it made has removed it, and a run that waited for it locked a file nobody else sees.
    bool LockedFileIsCurrent() const;

    std::string folder_;
    std::string path_;           // FOLDER/.rtrt-farm.lock
    std::string made_;           // the topmost folder this lock made, while not kept
    bool madeLockFile_ = false;  // the lock file is this lock's, while not kept
    int fd_ = -1;
};

}  // namespace rtrt
