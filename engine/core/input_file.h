#pragma once
// Whole input files read into memory, for every loader of user files. A path that is not a
// regular file is refused before it is opened (a device would be read for ever, a FIFO would
// block the open), and a file larger than the bound is refused before it is read, so that
// hostile input cannot exhaust memory.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rtrt {

inline constexpr size_t kMaxInputFileBytes = size_t{2} << 30;  // 2 GiB

// The size of the regular file path, of at most maxBytes; InputError(path, "", reason) otherwise.
uintmax_t CheckInputFile(const std::string& path, size_t maxBytes = kMaxInputFileBytes);
// The file's bytes; InputError(path, "", reason) for a missing, irregular, unreadable or
// oversized file.
std::string ReadInputFile(const std::string& path, size_t maxBytes = kMaxInputFileBytes);

// The files a command reads as its scene and assets (scene files, models, a glTF file's buffers
// and images) are remembered, so that an output naming one is refused (OutputFile) rather than
// written over: the command line's own check sees only the files it names, not those a scene
// refers to (`render model.gltf -o texture.png` had replaced the model's texture).
void RememberAssetFile(const std::string& path);
// ReadInputFile, remembering the file as an asset.
std::string ReadAssetFile(const std::string& path, size_t maxBytes = kMaxInputFileBytes);
// The path an asset file was read under when PATH names the same file (links followed), or
// nothing.
std::optional<std::string> AssetFileAt(const std::string& path);
// The asset files read so far, each once, as they were named when first read.
std::vector<std::string> AssetFilesRead();

}  // namespace rtrt
