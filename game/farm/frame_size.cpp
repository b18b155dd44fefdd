#include "game/farm/frame_size.h"

#include <cctype>
#include <cstring>
#include <fstream>

namespace rtrt {
namespace {

uint32_t BigEndian32(const unsigned char* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

// The next number of a PPM header, past whitespace and # comments.
bool PpmNumber(std::istream& in, uint32_t* value) {
    int c = in.get();
    while (c == '#' || std::isspace(c)) {
        if (c == '#')
            while (c != '\n' && c != EOF) c = in.get();
        c = in.get();
    }
    if (!std::isdigit(c)) return false;
    uint64_t v = 0;
    for (; std::isdigit(c) && v <= UINT32_MAX; c = in.get()) v = 10 * v + uint64_t(c - '0');
    *value = uint32_t(v);
    return v <= UINT32_MAX;
}

}  // namespace

bool ReadFrameSize(const std::string& path, FrameSize* size) {
    std::ifstream in(path, std::ios::binary);
    unsigned char head[24] = {};
    in.read(reinterpret_cast<char*>(head), 2);
    if (in.gcount() == 2 && head[0] == 'P' && head[1] == '6')
        return PpmNumber(in, &size->width) && PpmNumber(in, &size->height);
    // PNG: the 8-byte signature, then the IHDR chunk (length 13, type, width, height).
    static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    in.read(reinterpret_cast<char*>(head) + 2, 22);
    if (in.gcount() != 22 || std::memcmp(head, kPng, 8) != 0 || std::memcmp(head + 12, "IHDR", 4))
        return false;
    *size = {BigEndian32(head + 16), BigEndian32(head + 20)};
    return true;
}

}  // namespace rtrt
