#include "game/assets/image_io.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/output_file.h"

#if defined(RTRT_WITH_OIIO)
#include "game/image_library/image_library.h"
#endif

namespace rtrt {
namespace {

std::string Extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext;
}

[[maybe_unused]] bool IsFloatFormat(const std::string& ext) {  // used with OpenImageIO
    return ext == ".exr" || ext == ".pfm" || ext == ".hdr";
}

}  // namespace

Image CentredOn(const Image& frame, uint32_t width, uint32_t height) {
    if (frame.width == width && frame.height == height) return frame;
    Image fitted(width, height);
    const int dx = (int(frame.width) - int(width)) / 2;
    const int dy = (int(frame.height) - int(height)) / 2;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const int sx = int(x) + dx, sy = int(y) + dy;
            if (sx >= 0 && sy >= 0 && sx < int(frame.width) && sy < int(frame.height))
                fitted.At(x, y) = frame.At(uint32_t(sx), uint32_t(sy));
        }
    return fitted;
}

std::vector<uint8_t> EightBit(const Image& image, const OutputTransform& transform) {
    std::vector<uint8_t> bytes(image.pixels.size() * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const vec3 c = ApplyOutputTransform(image.pixels[i], transform);
        for (int k = 0; k < 3; ++k) bytes[3 * i + k] = DisplayByte(c[k]);
    }
    return bytes;
}

namespace {

// PPM or PFM bytes, written without OpenImageIO.
std::string EncodePortable(const Image& image, const std::string& ext,
                           const OutputTransform& transform) {
    std::string bytes;
    if (ext == ".pfm") {
        // PFM rows run bottom to top; a negative scale means little-endian.
        bytes =
            "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
        for (uint32_t y = image.height; y-- > 0;)
            for (uint32_t x = 0; x < image.width; ++x) {
                const vec3 c = FiniteRadiance(image.At(x, y));
                bytes.append(reinterpret_cast<const char*>(&c), sizeof(vec3));
            }
    } else {
        bytes =
            "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
        const std::vector<uint8_t> pixels = EightBit(image, transform);
        bytes.append(pixels.begin(), pixels.end());
    }
    return bytes;
}

#if defined(RTRT_WITH_OIIO)
// The image encoded by the image library (OpenImageIO) into memory, so that rtrt's own checked
// writes put it on disk: OpenImageIO's file writers (libpng's among them) do not all report a
// failed write.
std::vector<unsigned char> EncodeWithLibrary(const std::string& path, const Image& image,
                                             const OutputTransform& transform) {
    if (IsFloatFormat(Extension(path))) {
        std::vector<vec3> finite(image.pixels.size());
        std::transform(image.pixels.begin(), image.pixels.end(), finite.begin(),
                       [](vec3 c) { return FiniteRadiance(c); });
        return EncodeImage(path, image.width, image.height, true, finite.data());
    }
    return EncodeImage(path, image.width, image.height, false, EightBit(image, transform).data());
}
#endif

}  // namespace

void CheckImageSize(const std::string& path, uint32_t width, uint32_t height) {
    constexpr uint32_t kWebPMaxSide = 16383;  // the format's 14-bit sizes
    if (Extension(path) == ".webp" && (width > kWebPMaxSide || height > kWebPMaxSide))
        throw InputError(path, "",
                         "WebP images are at most 16383 pixels a side, and this one is " +
                             std::to_string(width) + "x" + std::to_string(height) +
                             "; give a smaller --size or another format");
}

void CheckImageFormat(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, "",
                         "is a folder; name an image file, e.g. " +
                             (std::filesystem::path(path) / "out.png").string());
    const std::string ext = Extension(path);
    // "a.png." has the extension "." (it had been named as a kind of image rtrt cannot write).
    if (ext.empty() || ext == ".")
        throw InputError(path, "", "the output needs an extension such as .png or .exr");
#if defined(RTRT_WITH_OIIO)
    if (ext != ".ppm" && ext != ".pfm") {
        if (!CanWriteImageFormat(path)) {
            // Said on the way out only: each format is asked by encoding a small image.
            std::string writable = ".ppm, .pfm";
            for (const char* other : {".png", ".exr", ".jpg", ".tif", ".hdr", ".bmp", ".tga",
                                      ".webp", ".gif", ".dpx", ".jp2"})
                if (CanWriteImageFormat(std::string("x") + other))
                    writable += std::string(", ") + other;
            throw InputError(path, "",
                             "rtrt cannot write " + ext + " images (it writes " + writable + ")");
        }
    }
#else
    if (ext != ".ppm" && ext != ".pfm")
        throw InputError(path, "", "this rtrt was built without OpenImageIO; write .ppm or .pfm");
#endif
}

void CheckImagePath(const std::string& path) {
    CheckImageFormat(path);
    CheckOutputPath(path);
}

void WriteImage(const std::string& path, const Image& image, const OutputTransform& transform) {
    CheckImageFormat(path);
    // The commands check their outputs before their work: a path that fails now (its folder
    // removed or made read-only meanwhile) is a failed write (exit 1), not bad input (2).
    try {
        CheckOutputPath(path);
    } catch (const InputError& e) {
        throw OutputError(e.File(), e.Reason());
    }
    const std::string ext = Extension(path);
    OutputFile file(path);
    if (ext == ".ppm" || ext == ".pfm") {
        const std::string bytes = EncodePortable(image, ext, transform);
        file.Write(bytes.data(), bytes.size());
    } else {
#if defined(RTRT_WITH_OIIO)
        const std::vector<unsigned char> bytes = EncodeWithLibrary(path, image, transform);
        file.Write(bytes.data(), bytes.size());
#endif
    }
    // Images carry no checksum, so they reach the disk before they take the output's name.
    file.Finish(/*durable=*/true);
    file.Commit();
}

bool CanReadImages() {
#if defined(RTRT_WITH_OIIO)
    return true;
#else
    return false;
#endif
}

namespace {

// Binary 8-bit PPM (P6), read without OpenImageIO: what the GPU machine's screenshots use.
Image ReadPpm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "", "cannot read image");
    char magic[2] = {};
    uint32_t width = 0, height = 0, maxValue = 0;
    in.read(magic, 2);
    in >> width >> height >> maxValue;
    if (magic[0] != 'P' || magic[1] != '6' || width == 0 || height == 0 || width > 16384 ||
        height > 16384 || maxValue != 255)
        throw InputError(path, "", "expected a binary 8-bit PPM (P6, maximum 255)");
    in.get();  // the one whitespace byte before the pixels
    std::vector<unsigned char> bytes(size_t(width) * height * 3);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size())))
        throw InputError(path, "", "the file ends before its pixels do");
    Image image(width, height);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = vec3(bytes[3 * i], bytes[3 * i + 1], bytes[3 * i + 2]) / 255.0f;
    return image;
}

#if defined(RTRT_WITH_OIIO)
// 2^28 texels is 16384 x 16384; more channels than 64 is no image rtrt reads.
std::string CheckReadShape(const ImageShape& shape) {
    if (shape.width >= 1 && shape.height >= 1 && shape.channels >= 1 && shape.channels <= 64 &&
        uint64_t(shape.width) * uint64_t(shape.height) <= (uint64_t(1) << 28))
        return "";
    return std::to_string(shape.width) + " x " + std::to_string(shape.height) + " texels of " +
           std::to_string(shape.channels) + " channels is not an image rtrt reads";
}
#endif

}  // namespace

Image ReadImage(const std::string& path) {
    if (std::filesystem::path(path).extension() == ".ppm") return ReadPpm(path);
#if defined(RTRT_WITH_OIIO)
    DecodedImage decoded;
    const std::string reason = ReadImageFile(path, &CheckReadShape, &decoded);
    if (!reason.empty()) throw InputError(path, "", reason);
    const int channels = decoded.shape.channels;
    std::vector<float> samples(decoded.samples.size() / sizeof(float));
    std::memcpy(samples.data(), decoded.samples.data(), samples.size() * sizeof(float));
    Image image(uint32_t(decoded.shape.width), uint32_t(decoded.shape.height));
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            image.pixels[i][c] = samples[i * channels + std::min(c, channels - 1)];
    return image;
#else
    throw InputError(path, "", "this rtrt reads only .ppm images (built without OpenImageIO)");
#endif
}

}  // namespace rtrt
