#pragma once
// The C interface between rtrt and its image library, the module rtrt_image_oiio (OpenImageIO's
// formats), which rtrt loads with dlopen() on the first image it reads or writes in one of those
// formats: a command that touches no such image never loads OpenImageIO and its ~260 libraries.
// Plain C types only, so that the two sides share no C++ object; whatever the module returns is
// put in memory that rtrt allocates through the sink.
#include <cstddef>
#include <cstdint>

namespace rtrt {

// A decoded image: width x height texels of `channels` samples of `sampleBytes` bytes each
// (4: float, 2: uint16_t, 1: uint8_t), row 0 the top.
struct ImageShape {
    int32_t width, height, channels, sampleBytes;
};
static_assert(sizeof(ImageShape) == 16);

// Where one call's result goes. allocate: room for `bytes` bytes of samples of `shape`, or of the
// encoded file when `shape` is null; null refuses (rtrt has recorded why). fail: why the call
// failed, one line; rtrt keeps the first reason it is given.
struct ImageSink {
    void* context;
    void* (*allocate)(void* context, const ImageShape* shape, size_t bytes);
    void (*fail)(void* context, const char* reason);
};

// The library's functions. Each returns 1 on success and 0, after sink->fail, on failure; none
// throws or keeps a pointer it was given.
struct ImageLibraryTable {
    // Whether the format of PATH's extension can be written (the file is not touched).
    int (*canWrite)(const char* path);
    // Encodes width x height RGB texels, float when isFloat, else uint8_t, in the format of
    // PATH's extension, into memory: rtrt writes the bytes itself, every write checked.
    int (*encode)(const char* path, int32_t width, int32_t height, int32_t isFloat, const void* rgb,
                  ImageSink* sink);
    // Reads the image file PATH (its first subimage) as float samples.
    int (*readFile)(const char* path, ImageSink* sink);
    // Decodes SIZE bytes of a FORMAT image ("png", "jpeg", "bmp", "gif") from memory, alpha left
    // straight, as uint16_t samples when the image has 16 bits, else uint8_t.
    int (*decode)(const unsigned char* bytes, size_t size, const char* format, ImageSink* sink);
};

// The module's one exported function; its name changes whenever the table does, so that a
// module of another rtrt fails to load rather than being called wrongly.
constexpr const char* kImageLibraryEntry = "rtrt_image_library_v1";
extern "C" const ImageLibraryTable* rtrt_image_library_v1();

}  // namespace rtrt
