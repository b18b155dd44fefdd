// libFuzzer target for the .rtmodel reader: any bytes must give a BLAS or an InputError, never a
// crash, a leak or undefined behaviour (build with the fuzz preset: clang, ASan, UBSan).
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "engine/bvh/blas/rtmodel.h"
#include "engine/bvh/blas/rtmodel_format.h"
#include "engine/core/error.h"

namespace {

using namespace rtrt::rtmodel;

// Random mutations almost never keep the checksums right, so the reader would stop there. The
// target reads each input twice: as given, and with both checksums made right again whenever
// the counts describe a file of the input's size, so that mutations reach the structural checks.
std::vector<uint8_t> Resealed(const uint8_t* data, size_t size) {
    std::vector<uint8_t> bytes(data, data + size);
    if (size < sizeof(RtModelHeader)) return bytes;
    RtModelHeader h;
    std::memcpy(&h, bytes.data(), sizeof(h));
    for (int s = 0; s < kSectionCount; ++s)
        if (h.counts[s] > size / kElementBytes[s]) return bytes;
    const Layout layout = LayoutOf(h.counts);
    if (layout.fileBytes == size) {
        h.payloadChecksum = PayloadChecksumOf(reinterpret_cast<const char*>(bytes.data()), layout);
        h.fileBytes = size;
    }
    SealHeader(h);
    std::memcpy(bytes.data(), &h, sizeof(h));
    return bytes;
}

void Read(const uint8_t* data, size_t size) {
    // The reader takes a path: an in-memory file stands in for one.
    static const int fd = memfd_create("rtmodel", 0);
    static const std::string path = "/proc/self/fd/" + std::to_string(fd);
    if (fd < 0 || ftruncate(fd, 0) != 0 || pwrite(fd, data, size, 0) != ssize_t(size)) return;
    try {
        const rtrt::Blas blas = rtrt::ReadRtModel(path);
        volatile uint64_t touched = blas.nodes.size() + blas.PrimCount() + blas.nodes4.size();
        (void)touched;
    } catch (const rtrt::InputError&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    Read(data, size);
    const std::vector<uint8_t> resealed = Resealed(data, size);
    Read(resealed.data(), resealed.size());
    return 0;
}
