#include "game/farm/frame_manifest.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/core/output_file.h"

namespace rtrt {
namespace fs = std::filesystem;

void AppendToManifest(const std::string& manifest, int frame, const std::string& path) {
    std::error_code ec;
    const uint64_t bytes = fs::file_size(path, ec);
    if (ec) throw OutputError(path, ec.message());
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on a + chain of strings here.
    std::string line = std::to_string(frame);
    line += '\t';
    line += fs::path(path).filename().string();
    line += '\t';
    line += std::to_string(bytes);
    line += '\t';
    line += HexDigest(HashFile(path));
    line += '\n';
    // Made by this call (O_EXCL), or another's to append to: only one made here is removed when
    // its first line fails.
    int fd = ::open(manifest.c_str(), O_RDWR | O_APPEND | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    const bool created = fd >= 0;
    if (!created && errno == EEXIST) fd = ::open(manifest.c_str(), O_RDWR | O_APPEND | O_CLOEXEC);
    if (fd < 0) throw OutputError(manifest, std::strerror(errno));
    // A line cut short by a crash of an earlier run (a requeued task appends to its file again)
    // is ended first, so that it does not swallow this one.
    const off_t size = ::lseek(fd, 0, SEEK_END);
    char last = '\n';
    if (size > 0 && ::pread(fd, &last, 1, size - 1) == 1 && last != '\n') line = '\n' + line;
    // One write of a short line: an appended line is whole or, after a crash, cut (and ignored).
    size_t done = 0;
    while (done < line.size()) {
        const ssize_t put = ::write(fd, line.data() + done, line.size() - done);
        if (put < 0 && errno == EINTR) continue;
        if (put <= 0) {
            // What was there stays as it was: the cut line is taken back (where that fails too,
            // readers skip a cut line), and a manifest this line was to begin is not left
            // behind empty.
            // Only while nothing else was appended after this line's start.
            const int error = put < 0 ? errno : ENOSPC;
            struct stat now {};
            const bool oursAtTheEnd = ::fstat(fd, &now) == 0 && now.st_size == size + off_t(done);
            if (oursAtTheEnd && done > 0) {
                [[maybe_unused]] const bool takenBack = ::ftruncate(fd, size) == 0;
            }
            ::close(fd);
            if (created && oursAtTheEnd && size == 0) ::unlink(manifest.c_str());
            throw OutputError(manifest, std::strerror(error));
        }
        done += size_t(put);
    }
    const int synced = ::fdatasync(fd) == 0 ? 0 : errno;
    const int closed = ::close(fd) == 0 ? 0 : errno;
    if (synced || closed) throw OutputError(manifest, std::strerror(synced ? synced : closed));
}

void CheckManifestPath(const std::string& path) {
    // A FIFO would block the open until something reads it, and a device is no record of frames.
    struct stat st;
    if (::stat(path.c_str(), &st) == 0) {
        if (!S_ISREG(st.st_mode))
            throw InputError("--manifest", path, "is not a regular file; name a file to append to");
        const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
        if (fd < 0) throw InputError("--manifest", path, std::strerror(errno));
        ::close(fd);
        return;
    }
    // A new manifest is made by the first finished frame, not here: input found bad after this
    // check leaves no empty manifest behind.
    try {
        CheckOutputPath(path);
    } catch (const InputError& e) {
        throw InputError("--manifest", path, e.Reason());
    }
}

namespace {

bool ParseLine(const std::string& line, ManifestEntry* e) {
    char file[256];
    unsigned long long bytes = 0, hash = 0;
    int frame = 0, used = 0;
    if (std::sscanf(line.c_str(), "%d\t%255[^\t]\t%llu\t%16llx%n", &frame, file, &bytes, &hash,
                    &used) != 4 ||
        size_t(used) != line.size() || frame < 0)
        return false;
    *e = {frame, file, bytes, hash};
    return true;
}

}  // namespace

std::map<int, std::vector<ManifestEntry>> ReadManifests(const std::string& folder) {
    std::vector<std::pair<fs::file_time_type, std::string>> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec))
        if (entry.path().extension() == ".tsv" && entry.is_regular_file(ec))
            files.emplace_back(entry.last_write_time(ec), entry.path().string());
    std::sort(files.begin(), files.end());
    std::map<int, std::vector<ManifestEntry>> entries;
    for (const auto& [time, path] : files) {
        std::ifstream in(path, std::ios::binary);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        size_t start = 0;
        for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
            ManifestEntry e;
            if (ParseLine(text.substr(start, end - start), &e)) entries[e.frame].push_back(e);
        }
    }
    return entries;
}

FrameCheck CheckFrames(const FarmJob& job, void (*progress)(int done, int total)) {
    // A file in a folder's place read as no frames done (--status said 0 of N), and the run then
    // failed to make the folder. A link to a folder (shared storage) is a folder.
    for (const std::string& dir : {FramesFolder(job.folder), ManifestFolder(job.folder)}) {
        std::error_code ec;
        const fs::file_status link = fs::symlink_status(dir, ec);
        if (!fs::exists(link)) continue;
        const fs::file_status target = fs::status(dir, ec);
        if (fs::is_directory(target)) continue;
        if (fs::is_symlink(link) && !fs::exists(target))
            throw InputError(dir, "",
                             "is a link to " + fs::read_symlink(dir, ec).string() +
                                 ", which is not there (is its storage mounted here?)");
        if (ec) throw OutputError(dir, ec.message());
        throw InputError(dir, "",
                         "is not a folder, where the job keeps its " +
                             fs::path(dir).filename().string() +
                             "; move it out of the way and run this again");
    }
    const std::map<int, std::vector<ManifestEntry>> entries =
        ReadManifests(ManifestFolder(job.folder));
    FrameCheck check;
    const FrameRange range = job.frames.frames;
    for (int frame = range.first; frame < range.end; ++frame) {
        if (progress) progress(frame - range.first, range.Count());
        const auto it = entries.find(frame);
        const std::string path = FrameFile(job, frame);
        std::error_code ec;
        const uint64_t bytes = fs::file_size(path, ec);
        if (it == entries.end() || ec) {
            check.missing.push_back(frame);
            continue;
        }
        // Done when any line vouches for the file as it is: two runs may both have written it.
        const std::string name = fs::path(path).filename().string();
        uint64_t hash = 0;
        bool hashed = false, whole = false;
        for (const ManifestEntry& e : it->second) {
            if (e.file != name || e.bytes != bytes) continue;
            if (!hashed) {
                try {
                    hash = HashFile(path);
                } catch (const InputError&) {
                    break;
                }
                hashed = true;
            }
            if (e.hash == hash) whole = true;
        }
        (whole ? check.done : check.corrupt).push_back(frame);
    }
    if (progress) progress(range.Count(), range.Count());
    return check;
}

std::string FramesText(const std::vector<int>& frames, size_t most) {
    std::string text;
    size_t shown = 0, i = 0;
    for (; i < frames.size() && shown < most; ++shown) {
        size_t j = i;
        while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
        if (!text.empty()) text += ", ";
        text += std::to_string(frames[i]);
        if (j > i) {
            text += '-';
            text += std::to_string(frames[j]);
        }
        i = j + 1;
    }
    if (i < frames.size()) text += ", ...";
    return text;
}

}  // namespace rtrt
