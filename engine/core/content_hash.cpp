#include "engine/core/content_hash.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/input_file.h"

// Inlined so that only the header is needed (the GPU machine brings headers, not libraries).
#define XXH_INLINE_ALL
#include <xxhash.h>

namespace rtrt {

struct StreamHash::State {
    XXH3_state_t xxh;
};

uint64_t HashBytes(const void* data, size_t size) { return XXH3_64bits(data, size); }

StreamHash::StreamHash() : state_(std::make_unique<State>()) { XXH3_64bits_reset(&state_->xxh); }
StreamHash::~StreamHash() = default;

void StreamHash::Update(const void* data, size_t size) {
    XXH3_64bits_update(&state_->xxh, data, size);
}

uint64_t StreamHash::Digest() const { return XXH3_64bits_digest(&state_->xxh); }

uint64_t HashFile(const std::string& path) {
    CheckInputFile(path, std::numeric_limits<size_t>::max());
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw InputError(path, "", std::strerror(errno));
    StreamHash hash;
    std::vector<char> buffer(size_t{1} << 20);
    size_t got = 0;
    while ((got = std::fread(buffer.data(), 1, buffer.size(), file.get())) > 0)
        hash.Update(buffer.data(), got);
    if (std::ferror(file.get())) throw InputError(path, "", "read error");
    return hash.Digest();
}

uint64_t HashFiles(std::vector<std::string> paths) {
    if (paths.size() == 1) return HashFile(paths[0]);
    std::vector<uint64_t> files;
    for (const std::string& path : paths) files.push_back(HashFile(path));
    // Sorted by value, not by path: the same files under other folders (a node's own copy of
    // the models) give the same hash.
    std::sort(files.begin(), files.end());
    StreamHash hash;
    hash.Update(files.data(), files.size() * sizeof(uint64_t));
    return hash.Digest();
}

std::string HexDigest(uint64_t hash) {
    char text[17];
    std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash));
    return text;
}

}  // namespace rtrt
