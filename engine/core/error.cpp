#include "engine/core/error.h"

#include <cstdio>

namespace rtrt {
namespace {
std::string Compose(const std::string& file, const std::string& field, const std::string& reason) {
    std::string message = file.empty() ? std::string("<input>") : file;
    if (!field.empty()) message += ": " + field;
    return WithoutControlCharacters(message + ": " + reason);
}
}  // namespace

InputError::InputError(std::string file, std::string field, std::string reason)
    : std::runtime_error(Compose(file, field, reason)),
      file_(std::move(file)),
      field_(std::move(field)),
      reason_(std::move(reason)) {}

OutputError::OutputError(std::string file, std::string reason)
    : std::runtime_error(WithoutControlCharacters(file + ": " + reason)),
      file_(std::move(file)),
      reason_(std::move(reason)) {}

std::string WithoutControlCharacters(std::string_view text) {
    std::string shown;
    shown.reserve(text.size());
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte != 0x7f) {
            shown += c;
            continue;
        }
        char escaped[5];
        std::snprintf(escaped, sizeof(escaped), "\\x%02x", byte);
        shown += escaped;
    }
    return shown;
}

}  // namespace rtrt
