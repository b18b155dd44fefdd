// glTF images decoded by OpenImageIO 2.4 (through the image library, game/image_library), from
// memory: tinygltf has already read the bytes from the .glb buffer view, the data: URI or the
// external file.
#include <tiny_gltf.h>

#include <cstring>
#include <exception>
#include <new>
#include <vector>

#include "game/gltf/gltf_image_loader.h"
#include "game/image_library/image_library.h"

namespace rtrt {
namespace {

// A corrupt header could otherwise ask for any allocation; 2^28 texels is 16384 x 16384.
constexpr uint64_t kMaxTexels = uint64_t(1) << 28;

// The bytes choose the reader, as they do for stb, so that both builds accept the same files
// whatever the mimeType says. glTF allows PNG and JPEG; BMP and GIF are what stb reads too
// (assets/models/textured_quads.gltf embeds a BMP). OIIO's other readers are never tried, so a
// hostile file cannot reach them.
const char* SniffFormat(const unsigned char* bytes, size_t size) {
    auto startsWith = [&](const char* magic, size_t n) {
        return size >= n && std::memcmp(bytes, magic, n) == 0;
    };
    if (startsWith("\x89PNG\r\n\x1a\n", 8)) return "png";
    if (startsWith("\xff\xd8\xff", 3)) return "jpeg";
    if (startsWith("BM", 2)) return "bmp";
    if (startsWith("GIF87a", 6) || startsWith("GIF89a", 6)) return "gif";
    return nullptr;
}

// Expands 1 to 4 channels of `wide` (16-bit) or 8-bit samples to RGBA in place of `image`'s,
// as stb does for tinygltf: grey fills R, G and B, a missing alpha is opaque.
void ExpandToRgba(tinygltf::Image& image, const std::vector<unsigned char>& samples, int channels,
                  bool wide) {
    const size_t bytes = wide ? 2 : 1, texels = size_t(image.width) * size_t(image.height);
    const uint16_t opaque = wide ? 0xffff : 0xff;
    image.image.resize(texels * 4 * bytes);
    for (size_t p = 0; p < texels; ++p) {
        auto sample = [&](int c) -> uint16_t {
            const unsigned char* s = &samples[(p * size_t(channels) + size_t(c)) * bytes];
            if (!wide) return s[0];
            uint16_t v;
            std::memcpy(&v, s, 2);
            return v;
        };
        const bool grey = channels <= 2, alpha = channels == 2 || channels == 4;
        const uint16_t rgba[4] = {sample(0), sample(grey ? 0 : 1), sample(grey ? 0 : 2),
                                  alpha ? sample(channels - 1) : opaque};
        for (int c = 0; c < 4; ++c) {
            unsigned char* d = &image.image[(p * 4 + size_t(c)) * bytes];
            if (wide)
                std::memcpy(d, &rgba[c], 2);
            else
                d[0] = uint8_t(rgba[c]);
        }
    }
    image.component = 4;
    image.bits = wide ? 16 : 8;
    image.pixel_type =
        wide ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
}

// What the importer reads: 1 to 4 channels, at most kMaxTexels, the size the image says it has.
std::string CheckShape(const ImageShape& shape, int reqWidth, int reqHeight) {
    if (shape.width < 1 || shape.height < 1 || shape.channels < 1 || shape.channels > 4)
        return std::to_string(shape.width) + " x " + std::to_string(shape.height) + " texels of " +
               std::to_string(shape.channels) + " channels; rtrt reads 1 to 4 channels";
    if (uint64_t(shape.width) * uint64_t(shape.height) > kMaxTexels)
        return std::to_string(shape.width) + " x " + std::to_string(shape.height) +
               " texels is more than rtrt reads (2^28)";
    if ((reqWidth > 0 && reqWidth != shape.width) || (reqHeight > 0 && reqHeight != shape.height))
        return "the image is " + std::to_string(shape.width) + " x " +
               std::to_string(shape.height) + ", its width and height say " +
               std::to_string(reqWidth) + " x " + std::to_string(reqHeight);
    return "";
}

// Fills `image` from the encoded bytes; returns why not, or "" on success. FILE: the glTF file.
std::string Decode(tinygltf::Image& image, int reqWidth, int reqHeight, const unsigned char* bytes,
                   int size, GltfImageFailure* failure) {
    const std::string& file = failure->file;
    if (bytes == nullptr || size <= 0) return "the image has no bytes";
    const char* format = SniffFormat(bytes, size_t(size));
    if (!format)
        return "not a PNG, JPEG, BMP or GIF image" +
               (image.mimeType.empty() ? "" : " (mimeType \"" + image.mimeType + "\")");
    DecodedImage decoded;
    const std::string reason = DecodeImage(
        bytes, size_t(size), format, file,
        [&](const ImageShape& shape) {
            const std::string why = CheckShape(shape, reqWidth, reqHeight);
            return why.empty() ? CountGltfTexels(failure, shape.width, shape.height) : why;
        },
        &decoded);
    if (!reason.empty()) return reason;
    image.width = decoded.shape.width;
    image.height = decoded.shape.height;
    ExpandToRgba(image, decoded.samples, decoded.shape.channels, decoded.shape.sampleBytes == 2);
    return "";
}

// tinygltf::LoadImageDataFunction.
bool LoadWithOiio(tinygltf::Image* image, const int index, std::string* err, std::string*,
                  int reqWidth, int reqHeight, const unsigned char* bytes, int size, void* user) {
    auto* failure = static_cast<GltfImageFailure*>(user);
    if (!DecodeGltfImage(failure, index)) return true;
    std::string reason;
    try {
        reason = Decode(*image, reqWidth, reqHeight, bytes, size, failure);
    } catch (const ImageLibraryError&) {  // rtrt's installation, not the file: rethrown whole
        failure->fatal = std::current_exception();
        return false;
    } catch (const std::bad_alloc&) {  // this machine's memory, not bad input: rethrown whole
        failure->fatal = std::current_exception();
        return false;
    } catch (const std::exception& e) {
        reason = std::string("decoding failed: ") + e.what();
    }
    if (reason.empty()) return true;
    failure->index = index;
    failure->reason = reason;
    if (err) *err += "image[" + std::to_string(index) + "]: " + reason + "\n";
    return false;
}

}  // namespace

void InstallGltfImageLoader(tinygltf::TinyGLTF& loader, GltfImageFailure* failure) {
    loader.SetImageLoader(&LoadWithOiio, failure);
}

}  // namespace rtrt
