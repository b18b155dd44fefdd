#pragma once
// Whole files read into memory for the mesh loaders, plain or gzip-compressed, at most 2 GiB
// after decompression so that hostile input cannot exhaust memory.
#include <string>

namespace rtrt {

// Throws InputError(path, "", reason) for a missing, irregular, unreadable or oversized file.
std::string ReadPlainFile(const std::string& path);
// Same, and for data that is not gzip or is corrupt.
std::string ReadGzipFile(const std::string& path);

}  // namespace rtrt
