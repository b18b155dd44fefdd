#include "engine/core/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <vector>

#include "engine/core/error.h"

namespace rtrt {
namespace {

std::string SizeText(size_t bytes) {
    if (bytes >= (size_t{1} << 30) && bytes % (size_t{1} << 30) == 0)
        return std::to_string(bytes >> 30) + " GiB";
    return std::to_string(bytes >> 20) + " MiB";
}

// A file as it was when read: a file system reuses a removed file's inode number at once (an
// editor that saves by renaming a new file over the old), so its size and change time tell the
// file read from another that took its number since.
struct AssetFile {
    dev_t device;
    ino_t inode;
    off_t size;
    timespec changed;
    std::string path;

    bool Is(const struct stat& info) const {
        return device == info.st_dev && inode == info.st_ino && size == info.st_size &&
               changed.tv_sec == info.st_ctim.tv_sec && changed.tv_nsec == info.st_ctim.tv_nsec;
    }
};

// Read by the loaders of every thread (a window's scene switch, the benches' loads).
std::mutex& AssetFilesMutex() {
    static std::mutex mutex;
    return mutex;
}
std::vector<AssetFile>& AssetFiles() {
    static std::vector<AssetFile> files;
    return files;
}

}  // namespace

void RememberAssetFile(const std::string& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return;
    std::lock_guard<std::mutex> lock(AssetFilesMutex());
    for (AssetFile& f : AssetFiles())
        if (f.device == info.st_dev && f.inode == info.st_ino) {
            // Read again (a window's scene switch), or another file with its number: as now.
            if (!f.Is(info)) f = {info.st_dev, info.st_ino, info.st_size, info.st_ctim, path};
            return;
        }
    AssetFiles().push_back({info.st_dev, info.st_ino, info.st_size, info.st_ctim, path});
}

std::string ReadAssetFile(const std::string& path, size_t maxBytes) {
    std::string bytes = ReadInputFile(path, maxBytes);
    RememberAssetFile(path);
    return bytes;
}

std::optional<std::string> AssetFileAt(const std::string& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return std::nullopt;
    std::lock_guard<std::mutex> lock(AssetFilesMutex());
    for (const AssetFile& f : AssetFiles())
        if (f.Is(info)) return f.path;
    return std::nullopt;
}

std::vector<std::string> AssetFilesRead() {
    std::lock_guard<std::mutex> lock(AssetFilesMutex());
    std::vector<std::string> paths;
    for (const AssetFile& f : AssetFiles()) paths.push_back(f.path);
    return paths;
}

uintmax_t CheckInputFile(const std::string& path, size_t maxBytes) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (ec) throw InputError(path, "", "cannot open file: " + ec.message());
    if (!std::filesystem::is_regular_file(status)) throw InputError(path, "", "not a regular file");
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(path, "", "cannot read file size: " + ec.message());
    if (size > maxBytes) {
        throw InputError(path, "", "file is larger than " + SizeText(maxBytes));
    }
    return size;
}

std::string ReadInputFile(const std::string& path, size_t maxBytes) {
    const uintmax_t size = CheckInputFile(path, maxBytes);
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
    std::string data(size, '\0');
    const size_t read = std::fread(data.data(), 1, data.size(), file.get());
    if (std::ferror(file.get())) {
        throw InputError(path, "", std::string("read error: ") + std::strerror(errno));
    }
    data.resize(read);
    return data;
}

}  // namespace rtrt
