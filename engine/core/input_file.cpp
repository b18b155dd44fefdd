#include "engine/core/input_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "engine/core/error.h"

namespace rtrt {
namespace {

std::string SizeText(size_t bytes) {
    if (bytes >= (size_t{1} << 30) && bytes % (size_t{1} << 30) == 0)
        return std::to_string(bytes >> 30) + " GiB";
    return std::to_string(bytes >> 20) + " MiB";
}

}  // namespace

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
