#pragma once
// rtrt's side of the image library (image_library_abi.h): the module found beside the running
// program (<prefix>/lib/rtrt/, in the build tree and installed alike), loaded on first use, and
// its calls with C++ results.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "game/image_library/image_library_abi.h"

namespace rtrt {

// The image library could not be loaded: a broken installation, not bad input (the CLI exits 1).
// what() reads "FILE: cannot load the image library (DETAIL); reinstall rtrt", FILE being the
// image that needed it.
class ImageLibraryError : public std::runtime_error {
  public:
    ImageLibraryError(const std::string& file, const std::string& detail);
};

// The library, loaded by the first call (later calls share it, or its error). Throws
// ImageLibraryError naming FILE when it cannot be loaded.
const ImageLibraryTable& ImageLibrary(const std::string& file);

// Decoded samples and their shape.
struct DecodedImage {
    ImageShape shape{};
    std::vector<unsigned char> samples;
};
// Accepts the shape of an image before its samples are allocated (returns "") or says why not.
using ShapeCheck = std::function<std::string(const ImageShape&)>;

// Whether PATH's extension names a format the library writes.
bool CanWriteImageFormat(const std::string& path);
// The encoded file for PATH's format; throws OutputError naming PATH if it cannot be encoded.
std::vector<unsigned char> EncodeImage(const std::string& path, uint32_t width, uint32_t height,
                                       bool isFloat, const void* rgb);
// Reads the image file PATH as float samples; returns why not, or "" on success.
std::string ReadImageFile(const std::string& path, const ShapeCheck& check, DecodedImage* image);
// Decodes a FORMAT image from memory (ImageLibraryTable::decode); FILE is the file that holds it,
// for the error when the library cannot be loaded. Returns why not, or "" on success.
std::string DecodeImage(const unsigned char* bytes, size_t size, const char* format,
                        const std::string& file, const ShapeCheck& check, DecodedImage* image);

}  // namespace rtrt
