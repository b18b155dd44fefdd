#include "game/assets/file_bytes.h"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "engine/core/error.h"

namespace rtrt {
namespace {

// Largest file, after decompression, that the loaders read: bounds memory on hostile input.
constexpr size_t kMaxFileBytes = size_t{2} << 30;

void CheckRegularFile(const std::string& path) {
    std::error_code ec;
    std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (ec) throw InputError(path, "", "cannot open file: " + ec.message());
    if (!std::filesystem::is_regular_file(status)) throw InputError(path, "", "not a regular file");
}

}  // namespace

std::string ReadPlainFile(const std::string& path) {
    CheckRegularFile(path);
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
    std::error_code ec;
    uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(path, "", "cannot read file size: " + ec.message());
    if (size > kMaxFileBytes) throw InputError(path, "", "file is larger than 2 GiB");
    std::string data(size, '\0');
    size_t read = std::fread(data.data(), 1, data.size(), file.get());
    if (std::ferror(file.get())) {
        throw InputError(path, "", std::string("read error: ") + std::strerror(errno));
    }
    data.resize(read);
    return data;
}

std::string ReadGzipFile(const std::string& path) {
    CheckRegularFile(path);
    std::unique_ptr<gzFile_s, int (*)(gzFile)> file(gzopen(path.c_str(), "rb"), &gzclose);
    if (!file) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
    gzbuffer(file.get(), 1 << 18);
    if (gzdirect(file.get())) throw InputError(path, "", "not a gzip file (bad magic)");
    constexpr size_t kChunk = size_t{1} << 22;
    std::string data;
    size_t size = 0;
    for (;;) {
        if (size == kMaxFileBytes) throw InputError(path, "", "decompressed data exceed 2 GiB");
        if (data.size() - size < kChunk) {
            data.resize(std::min(kMaxFileBytes, std::max(2 * data.size(), size + kChunk)));
        }
        unsigned want = static_cast<unsigned>(std::min(data.size() - size, kChunk));
        int got = gzread(file.get(), data.data() + size, want);
        if (got <= 0) break;
        size += static_cast<size_t>(got);
    }
    int status = Z_OK;
    const char* message = gzerror(file.get(), &status);
    if (status != Z_OK) throw InputError(path, "", std::string("corrupt gzip data: ") + message);
    data.resize(size);
    return data;
}

}  // namespace rtrt
