#pragma once
// The decoder tinygltf hands glTF images to (a .glb buffer view, a data: URI or an external file
// alike): OpenImageIO in builds with it (gltf_image_oiio.cpp, through the image library),
// tinygltf's own stb otherwise (gltf_image_stb.cpp). Either way the image comes back as 8- or
// 16-bit RGBA.
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

namespace tinygltf {
class TinyGLTF;
}

namespace rtrt {

// The texels of all of a file's images together: images can share one buffer view, so a small
// file can ask for any number of large images. 2^30 is 4 GiB of 8-bit RGBA.
inline constexpr uint64_t kMaxGltfFileTexels = uint64_t(1) << 30;

// The image a decode failed on, so that the importer's error names it ("images[2]"); tinygltf's
// own message does not say which field it was.
struct GltfImageFailure {
    int index = -1;  // -1 while every image decoded
    std::string reason;
    const std::vector<bool>* used = nullptr;  // images to decode (null: all of them)
    std::vector<int> skipped;                 // images left undecoded as unused
    std::string file;                         // the glTF file, for errors that are not an image's
    // An error of rtrt's own (its image library missing), to rethrow after the load.
    std::exception_ptr fatal;
    uint64_t texels = 0;  // decoded so far, at most kMaxGltfFileTexels
};

// "" when an image of width x height texels still fits the file's budget (and counts it), else
// why not.
std::string CountGltfTexels(GltfImageFailure* failure, int width, int height);

// Whether image `index` is to be decoded; an unused one is recorded in failure->skipped and left
// empty (the decoders call this first).
bool DecodeGltfImage(GltfImageFailure* failure, int index);

// Installs this build's decoder on `loader`; a failed decode is recorded in `*failure`, which
// must outlive the load.
void InstallGltfImageLoader(tinygltf::TinyGLTF& loader, GltfImageFailure* failure);

}  // namespace rtrt
