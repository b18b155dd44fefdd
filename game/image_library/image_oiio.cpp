// rtrt_image_oiio: the image library (image_library_abi.h) on OpenImageIO 2.4, the one part of rtrt
// that links it. Built as a module and loaded by rtrt at the first image that needs it.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "game/image_library/image_library_abi.h"

namespace rtrt {
namespace {

// OIIO's messages can span lines; rtrt's errors are one line.
std::string OneLine(std::string text, const char* otherwise) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text.empty() ? otherwise : text;
}

int Fail(ImageSink* sink, const std::string& reason) {
    sink->fail(sink->context, reason.c_str());
    return 0;
}

// Storage from the sink for the samples of SPEC read as TYPE; null (the sink told why) if refused.
void* SampleStorage(const OIIO::ImageSpec& spec, OIIO::TypeDesc type, ImageSink* sink) {
    // read_image writes every slice of a volume (a DDS volume texture): width x height x depth.
    if (spec.depth != 1) {
        Fail(sink,
             "a volume image of " + std::to_string(spec.depth) + " slices; rtrt reads flat images");
        return nullptr;
    }
    const ImageShape shape{spec.width, spec.height, spec.nchannels, int32_t(type.size())};
    // rtrt checks the shape before it allocates; a refused shape is never multiplied out here.
    const size_t bytes =
        spec.width > 0 && spec.height > 0 && spec.nchannels > 0
            ? size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels) * type.size()
            : 0;
    void* samples = sink->allocate(sink->context, &shape, bytes);
    if (!samples) Fail(sink, "cannot hold the image's " + std::to_string(bytes) + " bytes");
    return samples;
}

// Bytes of an image PATH's writer encodes into memory: empty where it cannot, and then *why.
std::vector<unsigned char> EncodeToMemory(const char* path, int32_t width, int32_t height,
                                          OIIO::TypeDesc type, const void* rgb, std::string* why) {
    // The bytes and the proxy outlive the writer, which may write through them as it closes.
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    auto out = OIIO::ImageOutput::create(path);
    if (!out || !out->supports("ioproxy") || !out->set_ioproxy(&proxy)) {
        *why = "OpenImageIO cannot encode this format into memory";
        return {};
    }
    // No time in the file (OpenImageIO writes the present one into EXR and TIFF where none is
    // given): the same image is the same bytes whenever it is written.
    OIIO::ImageSpec spec(width, height, 3, type);
    spec.attribute("DateTime", "");
    if (!out->open(path, spec) || !out->write_image(type, rgb) || !out->close()) {
        *why = "cannot encode: " + OneLine(out->geterror(), "OpenImageIO failed");
        return {};
    }
    if (bytes.empty()) *why = "cannot encode: OpenImageIO wrote no bytes";
    return bytes;
}

// Whether IN, opened as NAME, reads a 2x2 image.
bool ReadsTwoByTwo(OIIO::ImageInput& in, const std::string& name) {
    OIIO::ImageSpec spec;
    std::vector<unsigned char> rgb(2 * 2 * 3);
    return in.open(name, spec) && spec.width == 2 && spec.height == 2 &&
           in.read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data());
}

// Whether BYTES, encoded for PATH's format, read back from memory as a 2x2 image. A format
// whose reader is missing or cannot read from memory is taken on its encoding alone.
bool DecodesAsTwoByTwo(const char* path, std::vector<unsigned char>& bytes) {
    const std::string format = OIIO::Filesystem::extension(path, /*include_dot=*/false);
    // Declared before the reader, which closes through it when destroyed.
    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    auto in = OIIO::ImageInput::create(format);  // by format: a file name would be opened
    if (!in || !in->supports("ioproxy")) return true;
    in->set_ioproxy(&memory);
    return ReadsTwoByTwo(*in, "probe." + format);
}

// Whether a small image is encoded whole: a writer OpenImageIO has may still not write into
// memory (SGI, FITS), write nothing (the "null" format) or write a file without its pixels (JPEG
// 2000 into memory: the header boxes alone), which only encoding and decoding it show.
int CanWrite(const char* path) noexcept {
    try {
        const unsigned char rgb[2 * 2 * 3] = {};
        std::string why;
        std::vector<unsigned char> bytes =
            EncodeToMemory(path, 2, 2, OIIO::TypeDesc::UINT8, rgb, &why);
        return !bytes.empty() && DecodesAsTwoByTwo(path, bytes) ? 1 : 0;
    } catch (const std::exception&) {
        return 0;
    }
}

int Encode(const char* path, int32_t width, int32_t height, int32_t isFloat, const void* rgb,
           ImageSink* sink) noexcept {
    try {
        const OIIO::TypeDesc type = isFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
        std::string why;
        const std::vector<unsigned char> bytes =
            EncodeToMemory(path, width, height, type, rgb, &why);
        if (bytes.empty()) return Fail(sink, why);
        void* copy = sink->allocate(sink->context, nullptr, bytes.size());
        if (!copy) return Fail(sink, "cannot hold " + std::to_string(bytes.size()) + " bytes");
        std::memcpy(copy, bytes.data(), bytes.size());
        return 1;
    } catch (const std::exception& e) {
        return Fail(sink, std::string("cannot encode: ") + e.what());
    }
}

int ReadFile(const char* path, ImageSink* sink) noexcept {
    try {
        auto in = OIIO::ImageInput::open(path);
        if (!in)
            return Fail(sink, "cannot read image: " +
                                  OneLine(OIIO::geterror(), "OpenImageIO cannot open it"));
        const OIIO::ImageSpec& spec = in->spec();
        void* samples = SampleStorage(spec, OIIO::TypeDesc::FLOAT, sink);
        if (!samples) return 0;
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, samples))
            return Fail(sink, "cannot read image: " +
                                  OneLine(in->geterror(), "OpenImageIO cannot read it"));
        return 1;
    } catch (const std::exception& e) {
        return Fail(sink, std::string("cannot read image: ") + e.what());
    }
}

int Decode(const unsigned char* bytes, size_t size, const char* format, ImageSink* sink) noexcept {
    try {
        const std::string named = std::string(" (") + format + ")";
        // Declared before the reader, which closes through it when destroyed.
        OIIO::Filesystem::IOMemReader memory(bytes, size);
        auto input = OIIO::ImageInput::create(format);
        if (!input)
            return Fail(
                sink,
                OneLine(OIIO::geterror(), "OpenImageIO has no reader for this format") + named);
        // The proxy must be set before open(), which would otherwise look for a file by that name.
        input->set_ioproxy(&memory);
        // glTF's alpha is straight, as stb returns it; OIIO's PNG reader would premultiply it.
        OIIO::ImageSpec config, spec;
        config.attribute("oiio:UnassociatedAlpha", 1);
        if (!input->open(std::string("image.") + format, spec, config))
            return Fail(sink, OneLine(input->geterror(), "OpenImageIO could not open it") + named);
        // 16-bit PNGs stay 16-bit, as stb keeps them; everything else is read as 8-bit.
        const OIIO::TypeDesc type =
            spec.format == OIIO::TypeDesc::UINT16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
        void* samples = SampleStorage(spec, type, sink);
        if (!samples) return 0;
        if (!input->read_image(0, 0, 0, spec.nchannels, type, samples))
            return Fail(sink, OneLine(input->geterror(), "OpenImageIO could not read it") + named);
        return 1;
    } catch (const std::exception& e) {  // std::bad_alloc, or anything OIIO lets through
        return Fail(sink, std::string("decoding failed: ") + e.what());
    }
}

constexpr ImageLibraryTable kTable = {&CanWrite, &Encode, &ReadFile, &Decode};

}  // namespace

extern "C" __attribute__((visibility("default"))) const ImageLibraryTable* rtrt_image_library_v1() {
    return &kTable;
}

}  // namespace rtrt
