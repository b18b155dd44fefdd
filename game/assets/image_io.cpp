#include "game/assets/image_io.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "engine/core/error.h"

#if defined(RTRT_WITH_OIIO)
#include <OpenImageIO/imageio.h>
#endif

namespace rtrt {
namespace {

std::string Extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext;
}

bool IsFloatFormat(const std::string& ext) {
    return ext == ".exr" || ext == ".pfm" || ext == ".hdr";
}

void WritePortable(const std::string& path, const Image& image, const std::string& ext) {
    std::ofstream out(path, std::ios::binary);
    if (ext == ".pfm") {
        // PFM rows run bottom to top; a negative scale means little-endian.
        out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
        for (uint32_t y = image.height; y-- > 0;)
            out.write(reinterpret_cast<const char*>(&image.At(0, y)), sizeof(vec3) * image.width);
    } else {
        out << "P6\n" << image.width << " " << image.height << "\n255\n";
        for (const vec3& p : image.pixels)
            for (int c = 0; c < 3; ++c)
                out.put(char(uint8_t(std::clamp(p[c], 0.0f, 1.0f) * 255.0f + 0.5f)));
    }
    if (!out) throw InputError(path, "", "write failed");
}

}  // namespace

void CheckImagePath(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, "",
                         "is a folder; name an image file, e.g. " +
                             (std::filesystem::path(path) / "out.png").string());
    const std::string ext = Extension(path);
    if (ext.empty())
        throw InputError(path, "", "the output needs an extension such as .png or .exr");
#if defined(RTRT_WITH_OIIO)
    if (ext != ".ppm" && ext != ".pfm") {
        auto out = OIIO::ImageOutput::create(path);
        if (!out) throw InputError(path, "", "no image format is known for extension " + ext);
    }
#else
    if (ext != ".ppm" && ext != ".pfm")
        throw InputError(path, "", "this rtrt was built without OpenImageIO; write .ppm or .pfm");
#endif
    const auto dir = std::filesystem::path(path).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
        throw InputError(path, "", "the folder " + dir.string() + " does not exist");
    const std::string folder = dir.empty() ? std::string(".") : dir.string();
    if (access(folder.c_str(), W_OK) != 0)
        throw InputError(path, "",
                         "cannot write into the folder " + folder + ": " + std::strerror(errno));
}

void WriteImage(const std::string& path, const Image& image) {
    CheckImagePath(path);
    const std::string ext = Extension(path);
    // The temporary keeps the extension so the writer picks the same format.
    std::string name = ".";  // appended piecewise: GCC 12 warns falsely on a + chain here
    name += std::filesystem::path(path).stem().string();
    name += ".partial";
    name += ext;
    const std::string tmp = (std::filesystem::path(path).parent_path() / name).string();
    try {
        if (ext == ".ppm" || ext == ".pfm") {
            WritePortable(tmp, image, ext);
        } else {
#if defined(RTRT_WITH_OIIO)
            auto out = OIIO::ImageOutput::create(tmp);
            const bool isFloat = IsFloatFormat(ext);
            OIIO::ImageSpec spec(int(image.width), int(image.height), 3,
                                 isFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
            if (!out || !out->open(tmp, spec))
                throw InputError(path, "", "cannot open for writing: " + OIIO::geterror());
            bool ok;
            if (isFloat) {
                ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
            } else {
                std::vector<uint8_t> bytes(image.pixels.size() * 3);
                for (size_t i = 0; i < image.pixels.size(); ++i)
                    for (int c = 0; c < 3; ++c)
                        bytes[3 * i + c] =
                            uint8_t(std::clamp(image.pixels[i][c], 0.0f, 1.0f) * 255.0f + 0.5f);
                ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
            }
            if (!ok || !out->close())
                throw InputError(path, "", "write failed: " + out->geterror());
#endif
        }
        std::filesystem::rename(tmp, path);
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw;
    }
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

}  // namespace

Image ReadImage(const std::string& path) {
    if (std::filesystem::path(path).extension() == ".ppm") return ReadPpm(path);
#if defined(RTRT_WITH_OIIO)
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError(path, "", "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<float> data(size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
        throw InputError(path, "", "cannot read image: " + in->geterror());
    Image image(uint32_t(spec.width), uint32_t(spec.height));
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            image.pixels[i][c] = data[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
    return image;
#else
    throw InputError(path, "", "this rtrt reads only .ppm images (built without OpenImageIO)");
#endif
}

}  // namespace rtrt
