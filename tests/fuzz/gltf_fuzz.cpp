// libFuzzer target for glTF import: any bytes, as a .gltf (JSON) or a .glb (by its magic), must
// give a scene or an InputError, never a crash, a leak or undefined behaviour. tinygltf itself is
// Debian's uninstrumented library: this instruments rtrt's side of the import (GLB header, JSON
// field types, accessors, node graph, materials, animation, the BLAS builds).
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "engine/core/error.h"
#include "game/gltf/gltf_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // The importer takes a path: an in-memory file stands in for one. Relative URIs resolve
    // against /proc/self/fd, where nothing is a regular file but descriptors.
    static const int fd = memfd_create("gltf", 0);
    static const std::string path = "/proc/self/fd/" + std::to_string(fd);
    if (fd < 0 || ftruncate(fd, 0) != 0 || pwrite(fd, data, size, 0) != ssize_t(size)) return 0;
    try {
        const rtrt::LoadedScene scene = rtrt::LoadGltfScene(path);
        volatile uint64_t touched = scene.scene.instances.size() + scene.entities.size();
        (void)touched;
    } catch (const rtrt::InputError&) {
    }
    return 0;
}
