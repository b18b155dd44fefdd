#include "engine/core/error.h"

#include <cstdint>
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

namespace {

// The length of the well-formed UTF-8 sequence at TEXT[at] (1 to 4), and its code point; 0 where
// the bytes there are not one.
size_t Utf8Sequence(std::string_view text, size_t at, uint32_t* point) {
    const auto lead = static_cast<unsigned char>(text[at]);
    const size_t length = lead < 0x80           ? 1
                          : (lead >> 5) == 0x6  ? 2
                          : (lead >> 4) == 0xe  ? 3
                          : (lead >> 3) == 0x1e ? 4
                                                : 0;
    if (length == 0 || at + length > text.size()) return 0;
    uint32_t value = length == 1 ? lead : lead & (0x7f >> length);
    for (size_t k = 1; k < length; ++k) {
        const auto next = static_cast<unsigned char>(text[at + k]);
        if ((next & 0xc0) != 0x80) return 0;
        value = value << 6 | (next & 0x3f);
    }
    static constexpr uint32_t kLeast[5] = {0, 0, 0x80, 0x800, 0x10000};  // overlong below these
    if (value < kLeast[length] || value > 0x10ffff || (value >= 0xd800 && value <= 0xdfff))
        return 0;
    *point = value;
    return length;
}

// Code points a terminal acts on instead of showing: C0 and C1 controls, DEL, and the
// bidirectional overrides and isolates that reorder what follows them.
bool ActsOnTerminal(uint32_t point) {
    return point < 0x20 || (point >= 0x7f && point <= 0x9f) ||
           (point >= 0x202a && point <= 0x202e) || (point >= 0x2066 && point <= 0x2069);
}

}  // namespace

std::string WithoutControlCharacters(std::string_view text) {
    std::string shown;
    shown.reserve(text.size());
    for (size_t at = 0; at < text.size();) {
        uint32_t point = 0;
        const size_t length = Utf8Sequence(text, at, &point);
        // Invalid UTF-8 (a lone 0x9b is CSI on 8-bit terminals) is escaped byte by byte.
        const size_t escaped = length == 0 ? 1 : ActsOnTerminal(point) ? length : 0;
        if (escaped == 0) {
            shown.append(text.substr(at, length));
            at += length;
            continue;
        }
        for (size_t k = 0; k < escaped; ++k) {
            char hex[5];
            std::snprintf(hex, sizeof(hex), "\\x%02x", static_cast<unsigned char>(text[at + k]));
            shown += hex;
        }
        at += escaped;
    }
    return shown;
}

}  // namespace rtrt
