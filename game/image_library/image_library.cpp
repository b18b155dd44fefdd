#include "game/image_library/image_library.h"

#include <dlfcn.h>

#include <cctype>
#include <filesystem>
#include <map>
#include <mutex>
#include <new>

#include "engine/core/error.h"

namespace rtrt {
namespace {

struct Loaded {
    const ImageLibraryTable* table = nullptr;
    std::string error;  // why table is null
};

// RTRT_IMAGE_LIBRARY_DIR below the folder above the program's: bin/../lib/rtrt when installed,
// game/../lib/rtrt (and tests/../lib/rtrt) in the build tree.
Loaded Load() {
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) return {nullptr, "/proc/self/exe: " + error.message()};
    const std::string path =
        (exe.parent_path().parent_path() / RTRT_IMAGE_LIBRARY_DIR / RTRT_IMAGE_LIBRARY_FILE)
            .string();
    // Never closed: OpenImageIO's libraries stay until the program exits, as if linked. Bound
    // lazily, as a linked program's are: binding all their symbols now costs ~12 ms per image
    // command on this 2-core machine (a missing file or library still fails here, cleanly).
    void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!handle) return {nullptr, dlerror()};
    using Entry = const ImageLibraryTable* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, kImageLibraryEntry));
    if (!entry) return {nullptr, dlerror()};
    return {entry(), ""};
}

// Whether SIZE bytes are exactly the samples of SHAPE (and none of its numbers is out of range).
bool SizeMatches(const ImageShape& shape, size_t size) {
    if (shape.width < 1 || shape.height < 1 || shape.channels < 1 || shape.sampleBytes < 1)
        return false;
    size_t expected = 1;
    for (int32_t factor : {shape.width, shape.height, shape.channels, shape.sampleBytes})
        if (__builtin_mul_overflow(expected, size_t(factor), &expected)) return false;
    return expected == size;
}

// One call's results, gathered through its ImageSink.
class Collector {
  public:
    explicit Collector(const ShapeCheck& check) : check_(check) {}
    ImageSink Sink() { return {this, &Allocate, &Fail}; }
    std::string Reason() const {
        return reason.empty() ? "the image library gave no reason" : reason;
    }

    ImageShape shape{};
    std::vector<unsigned char> bytes;
    std::string reason;

  private:
    static void* Allocate(void* context, const ImageShape* shape, size_t size) noexcept {
        auto* self = static_cast<Collector*>(context);
        try {
            if (shape) {
                self->reason = self->check_ ? self->check_(*shape) : "";
                if (!self->reason.empty()) return nullptr;
                if (!SizeMatches(*shape, size)) {
                    self->reason = "the image library asked for storage that does not fit";
                    return nullptr;
                }
                self->shape = *shape;
            }
            if (size == 0) return nullptr;
            self->bytes.resize(size);
            return self->bytes.data();
        } catch (const std::exception& e) {  // std::bad_alloc
            self->reason = std::string("cannot hold the image: ") + e.what();
            return nullptr;
        }
    }
    static void Fail(void* context, const char* reason) noexcept {
        auto* self = static_cast<Collector*>(context);
        try {
            if (self->reason.empty()) self->reason = reason;
        } catch (const std::bad_alloc&) {
        }
    }

    const ShapeCheck& check_;
};

const ShapeCheck kAnyShape;

}  // namespace

ImageLibraryError::ImageLibraryError(const std::string& file, const std::string& detail)
    : std::runtime_error(file + ": cannot load the image library (" + detail +
                         "); reinstall rtrt") {}

const ImageLibraryTable& ImageLibrary(const std::string& file) {
    static const Loaded loaded = Load();
    if (!loaded.table) throw ImageLibraryError(file, loaded.error);
    return *loaded.table;
}

bool CanWriteImageFormat(const std::string& path) {
    // Asked once per extension and process: the answer costs an encoding and a decoding, and a
    // headless play asks for every frame.
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    static std::mutex mutex;
    static std::map<std::string, bool> known;
    std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = known.find(ext); it != known.end()) return it->second;
    const bool writable = ImageLibrary(path).canWrite(path.c_str()) != 0;
    known[ext] = writable;
    return writable;
}

std::vector<unsigned char> EncodeImage(const std::string& path, uint32_t width, uint32_t height,
                                       bool isFloat, const void* rgb) {
    const ImageLibraryTable& library = ImageLibrary(path);
    Collector result(kAnyShape);
    ImageSink sink = result.Sink();
    if (!library.encode(path.c_str(), int32_t(width), int32_t(height), isFloat, rgb, &sink))
        throw OutputError(path, result.Reason());
    return std::move(result.bytes);
}

std::string ReadImageFile(const std::string& path, const ShapeCheck& check, DecodedImage* image) {
    const ImageLibraryTable& library = ImageLibrary(path);
    Collector result(check);
    ImageSink sink = result.Sink();
    if (!library.readFile(path.c_str(), &sink)) return result.Reason();
    *image = {result.shape, std::move(result.bytes)};
    return "";
}

std::string DecodeImage(const unsigned char* bytes, size_t size, const char* format,
                        const std::string& file, const ShapeCheck& check, DecodedImage* image) {
    const ImageLibraryTable& library = ImageLibrary(file);
    Collector result(check);
    ImageSink sink = result.Sink();
    if (!library.decode(bytes, size, format, &sink)) return result.Reason();
    *image = {result.shape, std::move(result.bytes)};
    return "";
}

}  // namespace rtrt
