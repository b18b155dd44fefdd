#pragma once
// Fast non-cryptographic content hashes (XXH3-64, from Debian's libxxhash-dev): checksums of
// .rtmodel payloads and the source keys of the BLAS cache. Not for security: a file that means
// harm can carry a matching checksum, so loaders validate structure as well.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace rtrt {

uint64_t HashBytes(const void* data, size_t size);

// Hash of a stream given in pieces; equal to HashBytes of the concatenation.
class StreamHash {
  public:
    StreamHash();
    ~StreamHash();
    StreamHash(const StreamHash&) = delete;
    StreamHash& operator=(const StreamHash&) = delete;
    void Update(const void* data, size_t size);
    uint64_t Digest() const;

  private:
    struct State;
    std::unique_ptr<State> state_;
};

// Hash of a file's bytes; InputError (file, "", reason) when it cannot be read.
uint64_t HashFile(const std::string& path);

// One hash of several files' bytes, whatever their order and paths (the files' hashes are
// sorted): a lone file's is its HashFile. InputError naming a file that cannot be read.
uint64_t HashFiles(std::vector<std::string> paths);

// 16 lowercase hex digits.
std::string HexDigest(uint64_t hash);

}  // namespace rtrt
