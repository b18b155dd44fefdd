#pragma once
// Output files that appear whole or not at all: a temporary in the output's folder, every write,
// flush and close checked, renamed over the output only when complete, removed on every failure
// and on an interrupt (engine/core/interrupt.h).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace rtrt {

class OutputFile {
  public:
    // Creates the temporary (TemporaryPathFor) that becomes TARGET, or the file TARGET links to:
    // a link is written through, as a shell's > does, not replaced. A file replaced keeps its
    // permissions and, where this process may, its owner. Errors (OutputError) name TARGET,
    // never the temporary.
    explicit OutputFile(std::string target);
    ~OutputFile();  // removes the temporary unless committed
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    void Write(const void* data, size_t size);
    // Flushes to the disk when DURABLE (fsync), then closes; a failure of either is an error.
    void Finish(bool durable);
    // Renames the finished temporary over the target.
    void Commit();
    // Where the output is written until Commit, for another program writing it (ffmpeg).
    const std::string& TemporaryPath() const { return temp_; }

  private:
    std::string target_, file_, temp_;  // as named, the file it names, the temporary
    int fd_ = -1;
    uint64_t written_ = 0;
    bool committed_ = false;
};

// The temporary an output is written to before it takes TARGET's name: a hidden file in the same
// folder (so the rename stays on one filesystem) that carries the process id and the host name,
// so that an interrupt removes only this process's temporaries and two machines never share one.
std::string TemporaryPathFor(const std::string& target);
// What a temporary's file name (no folder) tells: the process that made it, and its host's tag
// (empty where the host has no name).
struct TemporaryName {
    long pid = 0;
    std::string host;
};
// NAME's process and host when it is a temporary that TemporaryPathFor made on any host, else
// nothing.
std::optional<TemporaryName> ParseTemporaryName(const std::string& name);
// The process id in NAME (a file name, no folder) when it is a temporary that TemporaryPathFor
// made on this host, else nothing: what is left behind by a process that was killed (SIGKILL)
// and can be removed once that process is gone.
std::optional<long> TemporaryOwnerHere(const std::string& name);

// PATH with its links followed to the file they name, which need not exist yet (an output is
// written there); InputError for a loop of links.
std::string FollowOutputLinks(const std::string& path);

// Whether A and B name one file: the same file where both exist (links, hard links and other
// spellings included), else the same path once links and dot-dots are resolved.
bool NameTheSameFile(const std::string& a, const std::string& b);

// InputError(path, "", reason) unless a whole file can be written at path (or where it links):
// its folder exists and takes new files, its name fits the file system, and it is not a folder,
// a device, a FIFO or a socket (which the rename would replace).
void CheckOutputPath(const std::string& path);

// InputError(path, "", reason) when PATH names a file of the scene this command read
// (RememberAssetFile): called once the scene is loaded, before the work whose result would go
// there, so that the clash fails at once rather than when the output is written.
void RefuseOutputOverAsset(const std::string& path);

// InputError(path, "", "cannot write into the folder FOLDER: reason") unless this process may
// create files in FOLDER.
void CheckFolderWritable(const std::string& path, const std::string& folder);

// Creates the folder path and its parents where missing; InputError(path, "", reason) when it
// cannot (a file is in the way, no permission) or cannot be written into.
void CreateOutputFolder(const std::string& path);

// TEXT written whole to PATH through its temporary, every write checked (OutputError otherwise);
// DURABLE flushes it to the disk before the rename.
void WriteWholeFile(const std::string& path, const std::string& text, bool durable);

}  // namespace rtrt
