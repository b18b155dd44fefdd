// glTF images in builds without OpenImageIO (the GPU machine's): tinygltf's stb decoder, wrapped
// only to record which image failed.
#include <tiny_gltf.h>

#include "game/gltf/gltf_image_loader.h"

namespace rtrt {
namespace {

bool LoadWithStb(tinygltf::Image* image, const int index, std::string* err, std::string* warn,
                 int reqWidth, int reqHeight, const unsigned char* bytes, int size, void* user) {
    if (!DecodeGltfImage(static_cast<GltfImageFailure*>(user), index)) return true;
    // A null option is tinygltf's default: channels expanded to RGBA.
    std::string reason;
    auto* failure = static_cast<GltfImageFailure*>(user);
    if (tinygltf::LoadImageData(image, index, &reason, warn, reqWidth, reqHeight, bytes, size,
                                nullptr)) {
        // stb has decoded it by now: the budget bounds what the file's images keep together.
        reason = CountGltfTexels(failure, image->width, image->height);
        if (reason.empty()) return true;
        image->image.clear();
        image->image.shrink_to_fit();
    }
    failure->index = index;
    failure->reason = reason.empty() ? "stb could not decode the image" : reason;
    if (err) *err += reason;
    return false;
}

}  // namespace

void InstallGltfImageLoader(tinygltf::TinyGLTF& loader, GltfImageFailure* failure) {
    loader.SetImageLoader(&LoadWithStb, failure);
}

}  // namespace rtrt
