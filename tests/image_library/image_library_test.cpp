// The image library loaded as rtrt loads it (the module beside the suite's folder) and each of its
// calls: encodings read back exactly, a shape refused before any sample is allocated, failures
// as one-line reasons.
#include "game/image_library/image_library.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "engine/core/error.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

// 3 x 2 RGB texels, row 0 the top.
const uint8_t kTexels[18] = {0, 1,  2,   50,  100, 150, 255, 254, 253,
                             7, 77, 177, 128, 64,  32,  9,   8,   7};

class ImageLibraryTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("rtrt_image_library_" + std::to_string(getpid()) + "_" + info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // The bytes saved as NAME in the test's folder; returns the path.
    std::string Save(const std::string& name, const std::vector<unsigned char>& bytes) const {
        const std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        return path;
    }
    fs::path dir_;
};

TEST_F(ImageLibraryTest, WritesTheFormatsOfOpenImageIO) {
    EXPECT_TRUE(CanWriteImageFormat("out.png"));
    EXPECT_TRUE(CanWriteImageFormat("out.exr"));
    EXPECT_FALSE(CanWriteImageFormat("out.nosuchformat"));
    // Formats OpenImageIO has a writer for that cannot encode into memory (SGI, FITS), or that
    // write nothing ("null"): refused by the check, not after the render.
    EXPECT_FALSE(CanWriteImageFormat("out.sgi"));
    EXPECT_FALSE(CanWriteImageFormat("out.fits"));
    EXPECT_FALSE(CanWriteImageFormat("out.null"));
    EXPECT_THROW(EncodeImage((dir_ / "out.nosuchformat").string(), 3, 2, false, kTexels),
                 OutputError);
}

TEST_F(ImageLibraryTest, PngReadsBackExactly) {
    const std::string name = (dir_ / "image.png").string();
    const std::string path = Save("image.png", EncodeImage(name, 3, 2, false, kTexels));
    DecodedImage image;
    ASSERT_EQ(ReadImageFile(path, {}, &image), "");
    EXPECT_EQ(image.shape.width, 3);
    EXPECT_EQ(image.shape.height, 2);
    ASSERT_EQ(image.shape.channels, 3);
    ASSERT_EQ(image.shape.sampleBytes, 4);
    ASSERT_EQ(image.samples.size(), sizeof(float) * 18);
    for (size_t i = 0; i < 18; ++i) {
        float value;
        std::memcpy(&value, &image.samples[i * sizeof(float)], sizeof(float));
        EXPECT_FLOAT_EQ(value, kTexels[i] / 255.0f) << "sample " << i;
    }
}

TEST_F(ImageLibraryTest, ExrKeepsFloats) {
    const float rgb[6] = {0.0f, 1.5f, -2.0f, 1e-3f, 65504.0f, 0.3333f};
    const std::string name = (dir_ / "image.exr").string();
    const std::string path = Save("image.exr", EncodeImage(name, 2, 1, true, rgb));
    DecodedImage image;
    ASSERT_EQ(ReadImageFile(path, {}, &image), "");
    ASSERT_EQ(image.samples.size(), sizeof(rgb));
    EXPECT_EQ(std::memcmp(image.samples.data(), rgb, sizeof(rgb)), 0);
}

// The same image encodes to the same bytes at any time: EXR and TIFF carried the time they were
// written (OpenImageIO fills in DateTime), so frames of one scene differed from run to run.
TEST_F(ImageLibraryTest, EncodingsDoNotDependOnTheTime) {
    const float rgb[6] = {0.0f, 1.5f, 0.25f, 1e-3f, 2.0f, 0.5f};
    for (const char* name : {"image.exr", "image.tif"}) {
        const std::string path = (dir_ / name).string();
        const std::vector<unsigned char> first = EncodeImage(path, 2, 1, true, rgb);
        ::sleep(1);  // the writer's clock counts whole seconds
        EXPECT_EQ(EncodeImage(path, 2, 1, true, rgb), first) << name;
    }
}

TEST_F(ImageLibraryTest, DecodesFromMemoryAsEightBit) {
    const std::vector<unsigned char> png =
        EncodeImage((dir_ / "image.png").string(), 3, 2, false, kTexels);
    DecodedImage image;
    ASSERT_EQ(DecodeImage(png.data(), png.size(), "png", "scene.gltf", {}, &image), "");
    EXPECT_EQ(image.shape.sampleBytes, 1);
    ASSERT_EQ(image.samples.size(), sizeof(kTexels));
    EXPECT_EQ(std::memcmp(image.samples.data(), kTexels, sizeof(kTexels)), 0);
}

TEST_F(ImageLibraryTest, ARefusedShapeIsTheReason) {
    const std::vector<unsigned char> png =
        EncodeImage((dir_ / "image.png").string(), 3, 2, false, kTexels);
    const ShapeCheck tooWide = [](const ImageShape& shape) {
        return shape.width > 2 ? std::string("too wide") : std::string();
    };
    DecodedImage image;
    EXPECT_EQ(DecodeImage(png.data(), png.size(), "png", "scene.gltf", tooWide, &image),
              "too wide");
    EXPECT_TRUE(image.samples.empty());
}

TEST_F(ImageLibraryTest, FailuresAreOneLine) {
    const unsigned char garbage[] = "\x89PNG\r\n\x1a\n but nothing after";
    DecodedImage image;
    const std::string reason =
        DecodeImage(garbage, sizeof(garbage), "png", "scene.gltf", {}, &image);
    EXPECT_NE(reason, "");
    EXPECT_NE(reason.find("(png)"), std::string::npos) << reason;
    EXPECT_EQ(reason.find('\n'), std::string::npos) << reason;
    const std::string missing = ReadImageFile((dir_ / "none.png").string(), {}, &image);
    EXPECT_EQ(missing.rfind("cannot read image: ", 0), 0u) << missing;
}

}  // namespace
}  // namespace rtrt
