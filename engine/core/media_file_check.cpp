#include "engine/core/media_file_check.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <optional>

namespace rtrt {
namespace {

// Reads from a regular file by offset; every read past the end comes back empty. Opened without
// waiting, so that a FIFO under a video's name is refused instead of waited on for ever.
class Bytes {
  public:
    explicit Bytes(const std::string& path)
        : fd_(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)) {
        struct stat st {};
        if (fd_ >= 0 && ::fstat(fd_, &st) == 0) {
            regular_ = S_ISREG(st.st_mode);
            size_ = uint64_t(st.st_size);
        }
    }
    ~Bytes() {
        if (fd_ >= 0) ::close(fd_);
    }
    Bytes(const Bytes&) = delete;
    Bytes& operator=(const Bytes&) = delete;
    bool Open() const { return fd_ >= 0; }
    bool Regular() const { return regular_; }
    uint64_t Size() const { return size_; }
    bool Read(uint64_t offset, void* out, size_t count) {
        if (offset > size_ || count > size_ - offset) return false;
        return ::pread(fd_, out, count, off_t(offset)) == ssize_t(count);
    }

  private:
    int fd_ = -1;
    bool regular_ = false;
    uint64_t size_ = 0;
};

uint64_t BigEndian(const uint8_t* p, int count) {
    uint64_t value = 0;
    for (int k = 0; k < count; ++k) value = value << 8 | p[k];
    return value;
}

// ISO base media (MP4, QuickTime): top-level boxes, each its size then its type, end to end.
std::string BoxesProblem(Bytes& file) {
    bool moov = false, mdat = false;
    uint64_t at = 0;
    while (at < file.Size()) {
        uint8_t head[16];
        if (!file.Read(at, head, 8)) return "is cut short inside a box's header";
        uint64_t size = BigEndian(head, 4), header = 8;
        if (size == 1) {
            if (!file.Read(at + 8, head + 8, 8)) return "is cut short inside a box's header";
            size = BigEndian(head + 8, 8);
            header = 16;
        } else if (size == 0) {
            size = file.Size() - at;  // the last box, to the end of the file
        }
        if (size < header) return "has a box smaller than its header";
        if (size > file.Size() - at) return "is cut short: a box goes past the end of the file";
        moov |= std::memcmp(head + 4, "moov", 4) == 0;
        mdat |= std::memcmp(head + 4, "mdat", 4) == 0;
        at += size;
    }
    if (!moov) return "is cut short: it has no index (moov box)";
    if (!mdat) return "holds no media data (mdat box)";
    return "";
}

// A Matroska variable-length integer at AT, its length in *length: an element's id keeps its
// length marker (as ids are written in the specification), a size drops it and is nothing when
// all its bits are ones ("unknown", as a writer leaves a segment it has not closed). False when
// it cannot be read.
bool ReadVint(Bytes& file, uint64_t at, bool isId, std::optional<uint64_t>* value, int* length) {
    uint8_t bytes[8];
    if (!file.Read(at, bytes, 1) || bytes[0] == 0) return false;
    *length = 1;
    while (!(bytes[0] & (0x80 >> (*length - 1)))) ++*length;
    if (!file.Read(at, bytes, size_t(*length))) return false;
    uint64_t raw = 0;
    for (int k = 0; k < *length; ++k) raw = raw << 8 | bytes[k];
    const uint64_t bits = 7ull * uint64_t(*length);
    const uint64_t data = raw & ((1ull << bits) - 1);
    if (isId)
        *value = raw;
    else
        *value = data == (1ull << bits) - 1 ? std::nullopt : std::optional<uint64_t>(data);
    return true;
}

// Matroska: the EBML header, then one segment whose size is written once the file is finished.
std::string MatroskaProblem(Bytes& file) {
    uint64_t at = 0;
    for (const uint64_t expected : {0x1A45DFA3ull, 0x18538067ull}) {
        std::optional<uint64_t> id, size;
        int idLength = 0, sizeLength = 0;
        if (!ReadVint(file, at, /*isId=*/true, &id, &idLength) ||
            !ReadVint(file, at + idLength, false, &size, &sizeLength))
            return "is cut short inside its headers";
        if (*id != expected)
            return expected == 0x18538067ull ? "has no segment after its header"
                                             : "is no Matroska file";
        if (!size) return "is cut short: its segment was never closed (size unknown)";
        at += uint64_t(idLength + sizeLength);
        if (*size > file.Size() - at)
            return expected == 0x18538067ull ? "is cut short: its segment goes past the end"
                                             : "is cut short inside its headers";
        if (expected == 0x18538067ull && at + *size != file.Size())
            return "holds more than its segment";
        at += *size;
    }
    return "";
}

// PNG: chunks (length, type, data, CRC) end to end up to IEND.
std::string PngProblem(Bytes& file) {
    uint64_t at = 8;
    while (at < file.Size()) {
        uint8_t head[8];
        if (!file.Read(at, head, 8)) return "is cut short inside a chunk's header";
        const uint64_t end = at + 12 + BigEndian(head, 4);
        if (end > file.Size()) return "is cut short: a chunk goes past the end of the file";
        if (std::memcmp(head + 4, "IEND", 4) == 0)
            return end == file.Size() ? "" : "holds bytes after its end (IEND)";
        at = end;
    }
    return "is cut short: it has no end (IEND chunk)";
}

}  // namespace

std::string MediaFileProblem(const std::string& path) {
    Bytes file(path);
    if (!file.Open()) return "cannot be read";
    if (!file.Regular()) return "is not a regular file";
    if (file.Size() == 0) return "is empty";
    std::array<uint8_t, 8> magic{};
    const size_t have = size_t(std::min<uint64_t>(file.Size(), magic.size()));
    file.Read(0, magic.data(), have);
    static constexpr uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static constexpr uint8_t kEbml[4] = {0x1A, 0x45, 0xDF, 0xA3};
    if (have == 8 && std::memcmp(magic.data(), kPng, 8) == 0) return PngProblem(file);
    if (have >= 4 && std::memcmp(magic.data(), kEbml, 4) == 0) return MatroskaProblem(file);
    if (have == 8 && std::memcmp(magic.data() + 4, "ftyp", 4) == 0) return BoxesProblem(file);
    return "is no MP4, QuickTime, Matroska or PNG file";
}

}  // namespace rtrt
