#pragma once
// The decoder tinygltf hands glTF images to (a .glb buffer view, a data: URI or an external file
// alike): OpenImageIO in builds with it (gltf_image_oiio.cpp, through the image library),
// tinygltf's own stb otherwise (gltf_image_stb.cpp). Either way the image comes back as 8- or
// 16-bit RGBA.
#include <exception>
#include <string>
#include <vector>

namespace tinygltf {
class TinyGLTF;
}

namespace rtrt {

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
};

// Whether image `index` is to be decoded; an unused one is recorded in failure->skipped and left
// empty (the decoders call this first).
bool DecodeGltfImage(GltfImageFailure* failure, int index);

// Installs this build's decoder on `loader`; a failed decode is recorded in `*failure`, which
// must outlive the load.
void InstallGltfImageLoader(tinygltf::TinyGLTF& loader, GltfImageFailure* failure);

}  // namespace rtrt
