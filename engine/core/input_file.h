#pragma once
// Whole input files read into memory, for every loader of user files. A path that is not a
// regular file is refused before it is opened (a device would be read for ever, a FIFO would
// block the open), and a file larger than the bound is refused before it is read, so that
// hostile input cannot exhaust memory.
#include <cstddef>
#include <cstdint>
#include <string>

namespace rtrt {

inline constexpr size_t kMaxInputFileBytes = size_t{2} << 30;  // 2 GiB

// The size of the regular file path, of at most maxBytes; InputError(path, "", reason) otherwise.
uintmax_t CheckInputFile(const std::string& path, size_t maxBytes = kMaxInputFileBytes);
// The file's bytes; InputError(path, "", reason) for a missing, irregular, unreadable or
// oversized file.
std::string ReadInputFile(const std::string& path, size_t maxBytes = kMaxInputFileBytes);

}  // namespace rtrt
