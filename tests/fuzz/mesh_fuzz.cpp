// libFuzzer target for the OBJ and PLY readers: any bytes, read as a PLY file when they start with
// "ply" and as an OBJ file otherwise, must give a mesh or an InputError, never a crash, a leak or
// undefined behaviour.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include "engine/core/error.h"
#include "game/assets/mesh_io.h"

namespace {

// The readers go by the extension: links with each name lead to one in-memory file.
struct MemoryFile {
    MemoryFile() {
        const std::string target = "/proc/self/fd/" + std::to_string(fd);
        const std::string base = "/tmp/rtrt_fuzz_mesh_" + std::to_string(getpid());
        for (std::string* link : {&obj, &ply}) {
            *link = base + (link == &obj ? ".obj" : ".ply");
            std::filesystem::remove(*link);
            std::filesystem::create_symlink(target, *link);
        }
    }
    ~MemoryFile() {
        std::error_code ec;
        std::filesystem::remove(obj, ec);
        std::filesystem::remove(ply, ec);
    }
    int fd = memfd_create("mesh", 0);
    std::string obj, ply;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const MemoryFile file;
    if (file.fd < 0 || ftruncate(file.fd, 0) != 0 ||
        pwrite(file.fd, data, size, 0) != ssize_t(size))
        return 0;
    const bool ply = size >= 3 && std::memcmp(data, "ply", 3) == 0;
    try {
        const rtrt::TriangleMesh mesh = rtrt::LoadMesh(ply ? file.ply : file.obj);
        volatile uint64_t touched = mesh.positions.size() + mesh.indices.size();
        (void)touched;
    } catch (const rtrt::InputError&) {
    }
    return 0;
}
