#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "engine/render_rt/image.h"
#include "engine/render_rt/output_transform.h"

namespace rtrt {

// Throws InputError unless path names a format rtrt can write (PNG, EXR, ... through
// OpenImageIO; PPM and PFM without it) in a folder that exists and can be written, and is not a
// folder itself. Called before the scene is loaded, so that bad paths fail before any work.
void CheckImagePath(const std::string& path);
// Only the format part of that: an extension rtrt can write, and path no folder.
void CheckImageFormat(const std::string& path);
// InputError when the format cannot hold an image of this size (WebP: 16383 pixels a side), so
// that it fails before the render rather than after.
void CheckImageSize(const std::string& path, uint32_t width, uint32_t height);

// Writes through a temporary file renamed into place, every write checked: a failure throws
// OutputError naming PATH with the system's reason and leaves no partial output.
// 8-bit formats store the output transform's display values * 255 rounded (kDisplayValues:
// clamp(value)); float formats store the linear values, untransformed.
void WriteImage(const std::string& path, const Image& image,
                const OutputTransform& transform = kDisplayValues);

// The bytes 8-bit outputs store: the display value * 255 rounded, RGB, row 0 the top.
std::vector<uint8_t> EightBit(const Image& image,
                              const OutputTransform& transform = kDisplayValues);

// FRAME centred on a WIDTH x HEIGHT image: cropped where it is larger, black around it where it
// is smaller. Recordings keep their first frame's size when the window is resized.
Image CentredOn(const Image& frame, uint32_t width, uint32_t height);

// Formats other than PPM and PFM go through the image library (OpenImageIO in the module
// rtrt_image_oiio, game/image_library), loaded at the first such image: an ImageLibraryError
// when it cannot be. Reading needs it too, except binary 8-bit .ppm, which every build reads.
// CanReadImages: whether other formats can be read (false in builds without OpenImageIO, the
// GPU machine's).
bool CanReadImages();
Image ReadImage(const std::string& path);

}  // namespace rtrt
