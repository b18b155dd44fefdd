#include "engine/bvh/blas/rtmodel.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <tbb/parallel_invoke.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>

#include "engine/bvh/blas/blas_check.h"
#include "engine/bvh/blas/rtmodel_format.h"
#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/core/math.h"
#include "engine/core/output_file.h"

namespace rtrt {
namespace {

using namespace rtmodel;

// The sections of a BLAS as byte ranges, in file order.
struct Bytes {
    const void* data;
    uint64_t count;
};
std::array<Bytes, kSectionCount> SectionsOf(const Blas& b) {
    return {{{b.nodes.data(), b.nodes.size()},
             {b.nodes4.data(), b.nodes4.size()},
             {b.triangles.data(), b.triangles.size()},
             {b.normals.data(), b.normals.size()},
             {b.spheres.data(), b.spheres.size()},
             {b.primIds.data(), b.primIds.size()},
             {b.uvs.data(), b.uvs.size()},
             {b.colors.data(), b.colors.size()}}};
}

class File {
  public:
    File(const std::string& path, int flags, mode_t mode = 0)
        : fd_(::open(path.c_str(), flags | O_CLOEXEC, mode)) {}
    ~File() {
        if (fd_ >= 0) ::close(fd_);
    }
    File(const File&) = delete;
    File& operator=(const File&) = delete;
    int Fd() const { return fd_; }
    bool Close() {
        const int fd = fd_;
        fd_ = -1;
        return ::close(fd) == 0;
    }

  private:
    int fd_;
};

// pread until SIZE bytes are in; false at end of file or on an error.
bool ReadAt(int fd, void* data, uint64_t size, uint64_t offset) {
    char* out = static_cast<char*>(data);
    while (size > 0) {
        const ssize_t got = ::pread(fd, out, size, off_t(offset));
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        out += got;
        size -= uint64_t(got);
        offset += uint64_t(got);
    }
    return true;
}

class Reader {
  public:
    // O_NONBLOCK: opening a FIFO would otherwise wait for a writer before fstat can refuse it;
    // it changes nothing for a regular file.
    explicit Reader(const std::string& path) : path_(path), file_(path, O_RDONLY | O_NONBLOCK) {}

    RtModelInfo ReadHeader() {
        if (file_.Fd() < 0) Fail("", errno == ENOENT ? "no such file" : std::strerror(errno));
        struct stat st;
        if (::fstat(file_.Fd(), &st) != 0 || !S_ISREG(st.st_mode)) Fail("", "not a regular file");
        const uint64_t size = uint64_t(st.st_size);
        // Bounded before any section is allocated: a sparse file is small on disk at any size.
        if (size > kMaxInputFileBytes)
            Fail("", std::to_string(size) + " bytes; rtrt reads model files of at most 2 GiB");
        if (size < sizeof(RtModelHeader) || !ReadAt(file_.Fd(), &h_, sizeof(h_), 0))
            Fail("header", "truncated: " + std::to_string(size) + " bytes, the header alone is " +
                               std::to_string(sizeof(RtModelHeader)));
        if (std::memcmp(h_.magic, kMagic, sizeof(kMagic)) != 0)
            Fail("header.magic", "not an .rtmodel file (it does not start with \"RTMODEL\")");
        if (h_.version != kRtModelVersion)
            Fail("header.version", "version " + std::to_string(h_.version) +
                                       ", this rtrt reads version " +
                                       std::to_string(kRtModelVersion) + "; convert it again");
        if (h_.headerBytes != sizeof(RtModelHeader))
            Fail("header.headerBytes", "expected " + std::to_string(sizeof(RtModelHeader)) +
                                           ", got " + std::to_string(h_.headerBytes));
        if (HashBytes(&h_, kHeaderHashedBytes) != h_.headerChecksum)
            Fail("header.headerChecksum", "checksum mismatch: the header is corrupt");
        if (h_.kind > uint32_t(GeometryKind::kSpheres))
            Fail("header.kind", "unknown geometry kind " + std::to_string(h_.kind));
        if (h_.builder > uint32_t(BvhBuilder::kSpatialSah))
            Fail("header.builder", "unknown builder id " + std::to_string(h_.builder));
        for (int s = 0; s < kSectionCount; ++s)
            if (h_.counts[s] > size / kElementBytes[s])
                Fail(std::string("header.counts.") + kSectionNames[s],
                     std::to_string(h_.counts[s]) + " elements cannot fit in a file of " +
                         std::to_string(size) + " bytes");
        const Aabb source = Info().sourceBounds;
        // Each plane alone: a sum of finite planes near the float limit overflows.
        if (!IsFinite(source.min) || !IsFinite(source.max) || source.IsEmpty())
            Fail("header.sourceBounds", "not finite, or min > max");
        layout_ = LayoutOf(h_.counts);
        if (layout_.fileBytes != size || h_.fileBytes != size)
            Fail("header.fileBytes", "the counts give " + std::to_string(layout_.fileBytes) +
                                         " bytes, the header says " + std::to_string(h_.fileBytes) +
                                         ", the file has " + std::to_string(size) +
                                         (size < layout_.fileBytes ? " (truncated)" : ""));
        return Info();
    }

    Blas ReadPayload() {
        Blas blas;
        blas.kind = GeometryKind(h_.kind);
        // The sections are read and hashed in parallel: loading is bound by page faults on the
        // new arrays, and both cores can take them.
        uint64_t hashes[kSectionCount];
        tbb::parallel_invoke([&] { hashes[kNodes] = ReadSection(kNodes, blas.nodes); },
                             [&] { hashes[kNodes4] = ReadSection(kNodes4, blas.nodes4); },
                             [&] { hashes[kTriangles] = ReadSection(kTriangles, blas.triangles); },
                             [&] { hashes[kNormals] = ReadSection(kNormals, blas.normals); },
                             [&] { hashes[kSpheres] = ReadSection(kSpheres, blas.spheres); },
                             [&] { hashes[kPrimIds] = ReadSection(kPrimIds, blas.primIds); },
                             [&] { hashes[kUvs] = ReadSection(kUvs, blas.uvs); },
                             [&] { hashes[kColors] = ReadSection(kColors, blas.colors); });
        if (PayloadChecksum(hashes) != h_.payloadChecksum)
            Fail("payloadChecksum", "checksum mismatch: the file is corrupt");
        CheckBlas(blas, path_, BvhBuilder(h_.builder) == BvhBuilder::kSpatialSah);
        blas.bounds = blas.nodes[0].Bounds();
        return blas;
    }

  private:
    [[noreturn]] void Fail(const std::string& field, const std::string& reason) const {
        throw InputError(path_, field, reason);
    }

    RtModelInfo Info() const {
        RtModelInfo info;
        info.key.sourceHash = h_.sourceHash;
        info.key.builder = BvhBuilder(h_.builder);
        info.key.maxLeafSize = h_.maxLeafSize;
        info.key.binCount = h_.binCount;
        info.key.revision = h_.revision;
        info.version = h_.version;
        info.sourceVertexCount = h_.sourceVertexCount;
        info.sourceBounds = {
            vec3(h_.sourceBoundsMin[0], h_.sourceBoundsMin[1], h_.sourceBoundsMin[2]),
            vec3(h_.sourceBoundsMax[0], h_.sourceBoundsMax[1], h_.sourceBoundsMax[2])};
        info.sahCost = h_.sahCost;
        info.fileBytes = h_.fileBytes;
        return info;
    }

    // One read straight into the array, then its padding; returns the hash of both.
    template <typename Vector>
    uint64_t ReadSection(Section s, Vector& out) const {
        out.resize(h_.counts[s]);
        const uint64_t bytes = h_.counts[s] * kElementBytes[s];
        if (!ReadAt(file_.Fd(), out.data(), bytes, layout_.offset[s]))
            Fail(kSectionNames[s], "read error");
        const uint64_t end = layout_.offset[s] + bytes;
        const uint64_t next = s + 1 < kSectionCount ? layout_.offset[s + 1] : layout_.fileBytes;
        char pad[kAlignment];
        if (!ReadAt(file_.Fd(), pad, next - end, end)) Fail(kSectionNames[s], "read error");
        StreamHash hash;
        hash.Update(out.data(), bytes);
        hash.Update(pad, next - end);
        return hash.Digest();
    }

    std::string path_;
    File file_;
    RtModelHeader h_{};
    Layout layout_{};
};

}  // namespace

RtModelKey MakeRtModelKey(uint64_t sourceHash, const BvhBuildOptions& options) {
    RtModelKey key;
    key.sourceHash = sourceHash;
    key.builder = options.builder;
    key.maxLeafSize = options.maxLeafSize;
    key.binCount = options.binCount;
    return key;
}

void WriteRtModel(const std::string& path, const Blas& blas, const RtModelInfo& info) {
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        throw InputError(path, "", "folder " + folder.string() + " does not exist");

    RtModelHeader h{};
    std::memcpy(h.magic, kMagic, sizeof(kMagic));
    h.version = kRtModelVersion;
    h.headerBytes = sizeof(RtModelHeader);
    h.kind = uint32_t(blas.kind);
    h.builder = uint32_t(info.key.builder);
    h.maxLeafSize = info.key.maxLeafSize;
    h.binCount = info.key.binCount;
    h.revision = info.key.revision;
    h.sourceVertexCount = info.sourceVertexCount;
    h.sourceHash = info.key.sourceHash;
    const auto sections = SectionsOf(blas);
    for (int s = 0; s < kSectionCount; ++s) h.counts[s] = sections[s].count;
    for (int a = 0; a < 3; ++a) {
        h.sourceBoundsMin[a] = info.sourceBounds.min[a];
        h.sourceBoundsMax[a] = info.sourceBounds.max[a];
    }
    h.sahCost = info.sahCost;
    const Layout layout = LayoutOf(h.counts);
    h.fileBytes = layout.fileBytes;

    static const char kZeros[kAlignment] = {};
    auto padOf = [&](int s) {
        const uint64_t end = layout.offset[s] + sections[s].count * kElementBytes[s];
        return (s + 1 < kSectionCount ? layout.offset[s + 1] : layout.fileBytes) - end;
    };
    uint64_t hashes[kSectionCount];
    for (int s = 0; s < kSectionCount; ++s) {
        StreamHash hash;
        hash.Update(sections[s].data, sections[s].count * kElementBytes[s]);
        hash.Update(kZeros, padOf(s));
        hashes[s] = hash.Digest();
    }
    h.payloadChecksum = PayloadChecksum(hashes);
    SealHeader(h);

    OutputFile out(path);
    out.Write(&h, sizeof(h));
    for (int s = 0; s < kSectionCount; ++s) {
        out.Write(sections[s].data, sections[s].count * kElementBytes[s]);
        out.Write(kZeros, padOf(s));
    }
    // No fsync: a file torn by a crash fails its checksums when read, and is rebuilt or reported.
    out.Finish(/*durable=*/false);
    // Renamed over the old file, never after removing it: an interrupt or a failed rename in
    // between had left no model at all.
    out.Commit();
}

Blas ReadRtModel(const std::string& path, RtModelInfo* info) {
    Reader reader(path);
    const RtModelInfo header = reader.ReadHeader();
    Blas blas = reader.ReadPayload();
    if (info) *info = header;
    return blas;
}

RtModelInfo ReadRtModelInfo(const std::string& path) { return Reader(path).ReadHeader(); }

bool IsRtModelPath(const std::string& path) {
    constexpr std::string_view kExt = ".rtmodel";
    if (path.size() < kExt.size()) return false;
    std::string tail = path.substr(path.size() - kExt.size());
    std::transform(tail.begin(), tail.end(), tail.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return tail == kExt;
}

}  // namespace rtrt
