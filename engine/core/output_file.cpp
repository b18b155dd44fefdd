#include "engine/core/output_file.h"

#include <fcntl.h>
#include <linux/magic.h>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/core/interrupt.h"

namespace rtrt {
namespace {

// This host's name as temporaries carry it: letters, digits and '-'.
const std::string& HostTag() {
    static const std::string host = [] {
        char name[256] = "";
        ::gethostname(name, sizeof(name) - 1);
        std::string text = name;
        for (char& c : text)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '-';
        return text;
    }();
    return host;
}

// NAME_MAX of the file systems rtrt writes to (ext4, XFS, tmpfs, NFS): bytes in one path component.
constexpr size_t kMaxFileNameBytes = 255;

// RTRT_TEST_FAIL_WRITE_AFTER=BYTES: writes past the first BYTES of each output fail with ENOSPC,
// for the disk-full test where no small filesystem can be mounted.
uint64_t InjectedWriteLimit() {
    static const uint64_t limit = [] {
        const char* text = std::getenv("RTRT_TEST_FAIL_WRITE_AFTER");
        return text && *text ? std::strtoull(text, nullptr, 10) : UINT64_MAX;
    }();
    return limit;
}
// write(2) with the injected limit applied; DONE is what the file holds so far.
ssize_t WriteSome(int fd, const void* data, size_t size, uint64_t done) {
    const uint64_t limit = InjectedWriteLimit();
    if (limit != UINT64_MAX) {
        if (done >= limit) {
            errno = ENOSPC;
            return -1;
        }
        if (size > limit - done) size = size_t(limit - done);
    }
    return ::write(fd, data, size);
}

}  // namespace

namespace {

// A link in a process's descriptor folder (/proc/PID/fd, which /dev/fd and /dev/stdout lead to,
// however the way there is spelled): the kernel's name for an open descriptor, whose text is no
// path to write beside ("pipe:[N]", or a file the shell opened for appending, which a rename over
// it would replace, losing what it held). Told by the filesystem, not the spelling.
bool IsDescriptorLink(const std::string& link) {
    std::error_code ec;
    const std::filesystem::path folder =
        std::filesystem::canonical(std::filesystem::absolute(link, ec).parent_path(), ec);
    struct statfs mounted {};
    return !ec && folder.filename() == "fd" && ::statfs(folder.c_str(), &mounted) == 0 &&
           mounted.f_type == PROC_SUPER_MAGIC;
}

}  // namespace

std::string FollowOutputLinks(const std::string& path) {
    namespace fs = std::filesystem;
    std::string file = path;
    for (int hop = 0; hop < 40; ++hop) {  // the kernel's own bound (ELOOP)
        std::error_code ec;
        if (!fs::is_symlink(fs::symlink_status(file, ec))) return file;
        const fs::path link = fs::read_symlink(file, ec);
        if (ec) return file;
        if (IsDescriptorLink(file)) return file;  // not followed
        file = link.is_absolute() ? link.string() : (fs::path(file).parent_path() / link).string();
    }
    throw InputError(path, "", "is a loop of links");
}

// InputError unless FILE (PATH with its links followed) is a file rtrt may write through its
// temporary: not a link to a process's descriptor.
void CheckNotDescriptor(const std::string& path, const std::string& file) {
    std::error_code ec;
    if (std::filesystem::is_symlink(std::filesystem::symlink_status(file, ec)))
        throw InputError(path, "",
                         "leads to " + file +
                             ", an open descriptor (as /dev/stdout does); rtrt writes whole "
                             "files through a temporary: name a file, and read it from there");
}

bool NameTheSameFile(const std::string& a, const std::string& b) {
    struct stat sa {
    }, sb{};
    if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    std::error_code ea, eb;
    namespace fs = std::filesystem;
    const fs::path ca = fs::weakly_canonical(fs::absolute(FollowOutputLinks(a), ea), ea);
    const fs::path cb = fs::weakly_canonical(fs::absolute(FollowOutputLinks(b), eb), eb);
    return !ea && !eb && ca == cb;
}

void CheckOutputPath(const std::string& path) {
    if (path.empty()) throw InputError(path, "", "the output needs a file name");
    // Where other tools read "-" as standard output, rtrt had made a file of that name.
    if (path == "-")
        throw InputError(path, "",
                         "rtrt writes outputs to files, not to standard output: name a file (./- "
                         "for a file called -)");
    const std::string file = FollowOutputLinks(path);
    CheckNotDescriptor(path, file);
    // Named in the reasons where a link led elsewhere.
    const std::string where = file == path ? "" : " (where the link leads: " + file + ")";
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(file, ec);
    if (std::filesystem::is_directory(status))
        throw InputError(path, "", "is a folder" + where + "; name a file in it");
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw InputError(path, "", "is not a regular file (a device, FIFO or socket)" + where);
    // A write-protected file would be replaced all the same (the rename needs only the folder),
    // and become the writer's: refused, as cp refuses it.
    if (std::filesystem::exists(status) && access(file.c_str(), W_OK) != 0)
        throw InputError(path, "",
                         "is write-protected" + where +
                             ": make it writable (chmod u+w) or remove it to write over it");
    const std::filesystem::path folder = std::filesystem::path(file).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder, ec)) {
        // A file where a folder of the path should be is named as such, not as a missing folder.
        std::filesystem::path existing = folder;
        while (!existing.empty() && !std::filesystem::exists(existing, ec))
            existing = existing.parent_path();
        if (!existing.empty() && !std::filesystem::is_directory(existing, ec))
            throw InputError(path, "", existing.string() + " is a file, not a folder");
        throw InputError(path, "", "the folder " + folder.string() + " does not exist");
    }
    // Else the rename into place fails, after all the work.
    const std::string name = std::filesystem::path(file).filename().string();
    if (name.size() > kMaxFileNameBytes)
        throw InputError(path, "",
                         "the file name is too long (" + std::to_string(name.size()) +
                             " bytes; file systems take at most " +
                             std::to_string(kMaxFileNameBytes) + ")");
    CheckFolderWritable(path, folder.empty() ? std::string(".") : folder.string());
}

void CheckFolderWritable(const std::string& path, const std::string& folder) {
    auto refuse = [&](const std::string& why) {
        throw InputError(path, "", "cannot write into the folder " + folder + ": " + why);
    };
    if (access(folder.c_str(), W_OK) != 0) refuse(std::strerror(errno));
    // access() passes folders that take no new file (/proc and /sys as root, some FUSE and
    // network mounts), where the output would fail only after the work: a file is made and
    // removed again, as the output's temporary would be.
    // Made new (O_EXCL, never through a link or into a FIFO someone left under its name).
    const std::string probe = TemporaryPathFor((std::filesystem::path(folder) / "check").string());
    TemporariesLock lock;
    const int flags = O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC;
    int fd = ::open(probe.c_str(), flags, 0600);
    int error = errno;
    if (fd < 0 && error == EEXIST && ::unlink(probe.c_str()) == 0) {
        fd = ::open(probe.c_str(), flags, 0600);
        error = errno;
    }
    if (fd < 0) {
        // A full disk, a quota or an I/O error is the work failing (exit 1), not bad input.
        if (error == ENOSPC || error == EDQUOT || error == EIO)
            throw OutputError(
                path, "cannot write into the folder " + folder + ": " + std::strerror(error));
        refuse(error == ENOENT ? "it takes no new files" : std::strerror(error));
    }
    ::close(fd);
    ::unlink(probe.c_str());
}

void CreateOutputFolder(const std::string& path) {
    std::error_code ec;
    std::filesystem::create_directories(path, ec);
    if (ec) throw InputError(path, "", "cannot create the folder: " + ec.message());
    if (!std::filesystem::is_directory(path, ec)) throw InputError(path, "", "is not a folder");
    CheckFolderWritable(path, path);
}

void RefuseOutputOverAsset(const std::string& path) {
    if (path.empty()) return;
    if (const std::optional<std::string> asset = AssetFileAt(FollowOutputLinks(path)))
        throw InputError(path, "",
                         "is a file of the scene this command read (" + *asset +
                             "), which would be written over; name another file");
}

OutputFile::OutputFile(std::string target)
    : target_(std::move(target)),
      file_(FollowOutputLinks(target_)),
      temp_(TemporaryPathFor(file_)) {
    CheckNotDescriptor(target_, file_);
    // The rename would put a regular file in place of a device or a FIFO, or fail on a folder
    // only once the output is written.
    struct stat old {};
    const bool replacing = ::stat(file_.c_str(), &old) == 0;
    if (replacing && !S_ISREG(old.st_mode)) {
        throw InputError(target_, "", "is not a regular file (a folder, device, FIFO or socket)");
    }
    if (replacing) RefuseOutputOverAsset(target_);
    TemporariesLock lock;
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) throw OutputError(target_, std::strerror(errno));
    lock.Register(temp_);
    if (replacing) {
        // A private file stays private; an owner other than this process (root writing a user's
        // file) is kept where the system lets it be given away.
        const bool sameOwner = old.st_uid == ::geteuid() && old.st_gid == ::getegid();
        const bool owned = sameOwner || ::fchown(fd_, old.st_uid, old.st_gid) == 0;
        ::fchmod(fd_, old.st_mode & (owned ? 07777 : 0777));  // set-id bits only as the owner's
    }
}

OutputFile::~OutputFile() {
    if (fd_ >= 0) ::close(fd_);
    if (committed_) return;
    TemporariesLock lock;
    ::unlink(temp_.c_str());
    lock.Unregister(temp_);
}

void OutputFile::Write(const void* data, size_t size) {
    const char* in = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t put = WriteSome(fd_, in, size, written_);
        if (put < 0 && errno == EINTR) continue;
        if (put <= 0) throw OutputError(target_, std::strerror(put < 0 ? errno : ENOSPC));
        in += put;
        size -= size_t(put);
        written_ += uint64_t(put);
    }
}

void OutputFile::Finish(bool durable) {
    if (durable && ::fsync(fd_) != 0) throw OutputError(target_, std::strerror(errno));
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) throw OutputError(target_, std::strerror(errno));
}

void OutputFile::Commit() {
    TemporariesLock lock;  // an interrupt comes before the rename or after the unregistering
    if (std::rename(temp_.c_str(), file_.c_str()) != 0)
        throw OutputError(target_, std::strerror(errno));
    committed_ = true;
    lock.Unregister(temp_);
}

std::optional<TemporaryName> ParseTemporaryName(const std::string& name) {
    // .STEM.partialPID[-HOST][.EXT], as TemporaryPathFor makes it on any host.
    const size_t at = name.rfind(".partial");
    if (name.size() < 2 || name[0] != '.' || at == std::string::npos || at == 0)
        return std::nullopt;
    size_t end = at + 8;
    long pid = 0;
    for (; end < name.size() && std::isdigit(static_cast<unsigned char>(name[end])); ++end) {
        pid = pid * 10 + (name[end] - '0');
        if (pid > 1L << 31) return std::nullopt;
    }
    if (end == at + 8 || pid <= 0) return std::nullopt;
    TemporaryName parsed{pid, ""};
    if (end < name.size() && name[end] == '-') {
        const size_t hostEnd = std::min(name.find('.', end), name.size());
        parsed.host = name.substr(end + 1, hostEnd - end - 1);
        const bool tag =
            !parsed.host.empty() && std::all_of(parsed.host.begin(), parsed.host.end(), [](char c) {
                return std::isalnum(static_cast<unsigned char>(c)) || c == '-';
            });
        if (!tag) return std::nullopt;
        end = hostEnd;
    }
    const std::string extension = name.substr(end);
    if (!extension.empty() && (extension[0] != '.' || extension.find('.', 1) != std::string::npos))
        return std::nullopt;
    return parsed;
}

std::optional<long> TemporaryOwnerHere(const std::string& name) {
    const std::optional<TemporaryName> parsed = ParseTemporaryName(name);
    if (!parsed || parsed->host != HostTag()) return std::nullopt;
    return parsed->pid;
}

std::string TemporaryPathFor(const std::string& target) {
    const size_t slash = target.rfind('/');
    const std::string folder = slash == std::string::npos ? "" : target.substr(0, slash + 1);
    const std::string name = slash == std::string::npos ? target : target.substr(slash + 1);
    const size_t dot = name.rfind('.');
    const std::string stem = dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
    const std::string ext = dot == std::string::npos || dot == 0 ? "" : name.substr(dot);
    // The host too: processes of several machines writing into one shared folder (a farm's
    // tasks) may have the same id. The extension stays last, for tools that go by it.
    const std::string& host = HostTag();
    std::string suffix = ".partial";
    suffix += std::to_string(::getpid());
    if (!host.empty()) suffix += "-" + host;
    suffix += ext;
    // A name the file system takes may be too long with the suffix: the stem is then cut (at a
    // UTF-8 character's start) and a hash of the whole name keeps temporaries of different
    // targets apart.
    std::string shortStem = stem;
    if (1 + stem.size() + suffix.size() > kMaxFileNameBytes) {
        const size_t room = kMaxFileNameBytes - std::min(kMaxFileNameBytes, suffix.size() + 18);
        size_t cut = std::min(room, stem.size());
        while (cut > 0 && (static_cast<unsigned char>(stem[cut]) & 0xc0) == 0x80) --cut;
        char hash[18];
        std::snprintf(hash, sizeof(hash), "~%016llx",
                      static_cast<unsigned long long>(std::hash<std::string>{}(name)));
        shortStem = stem.substr(0, cut) + hash;
    }
    std::string path = folder;  // appended piecewise, as GCC 12 warns falsely on a + chain
    path += '.';
    path += shortStem;
    path += suffix;
    return path;
}

void WriteWholeFile(const std::string& path, const std::string& text, bool durable) {
    OutputFile file(path);
    file.Write(text.data(), text.size());
    file.Finish(durable);
    file.Commit();
}

}  // namespace rtrt
