#include "game/assets/file_bytes.h"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "engine/core/error.h"
#include "engine/core/input_file.h"

namespace rtrt {
std::string ReadPlainFile(const std::string& path) { return ReadAssetFile(path); }

std::string ReadGzipFile(const std::string& path) {
    CheckInputFile(path, kMaxInputFileBytes);
    RememberAssetFile(path);
    std::unique_ptr<gzFile_s, int (*)(gzFile)> file(gzopen(path.c_str(), "rb"), &gzclose);
    if (!file) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
    gzbuffer(file.get(), 1 << 18);
    if (gzdirect(file.get())) throw InputError(path, "", "not a gzip file (bad magic)");
    constexpr size_t kChunk = size_t{1} << 22;
    std::string data;
    size_t size = 0;
    for (;;) {
        if (size == kMaxInputFileBytes)
            throw InputError(path, "", "decompressed data exceed 2 GiB");
        if (data.size() - size < kChunk) {
            data.resize(std::min(kMaxInputFileBytes, std::max(2 * data.size(), size + kChunk)));
        }
        unsigned want = static_cast<unsigned>(std::min(data.size() - size, kChunk));
        int got = gzread(file.get(), data.data() + size, want);
        if (got <= 0) break;
        size += static_cast<size_t>(got);
    }
    int status = Z_OK;
    const char* message = gzerror(file.get(), &status);
    if (status != Z_OK) {
        // zlib puts the path before its reason; the error names the file once.
        std::string reason = message;
        if (reason.starts_with(path + ": ")) reason.erase(0, path.size() + 2);
        throw InputError(path, "", "corrupt gzip data: " + reason);
    }
    data.resize(size);
    return data;
}

}  // namespace rtrt
