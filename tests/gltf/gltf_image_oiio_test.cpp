// glTF images decoded through OpenImageIO (builds with RTRT_WITH_OIIO): the textured asset and
// PNGs in every container reach the texel array exactly, and a JPEG, which OIIO's libjpeg and
// tinygltf's stb decode differently, comes out as OIIO decodes it, so the test fails if the
// OIIO loader is not the one installed.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "engine/core/error.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;
using test::GltfBuilder;
using Json = nlohmann::json;
using Bytes = std::vector<uint8_t>;

constexpr int kNearest = 9728, kClamp = 33071;

class GltfOiioTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("rtrt_gltf_oiio_" + std::to_string(getpid()) + "_" + info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // `samples` (row 0 the top) encoded by OpenImageIO's writer for `name`'s extension.
    Bytes Encode(const std::string& name, int width, int height, int channels, OIIO::TypeDesc type,
                 const void* samples) const {
        const std::string path = (dir_ / name).string();
        auto out = OIIO::ImageOutput::create(path);
        EXPECT_TRUE(out) << OIIO::geterror();
        if (!out) return {};
        OIIO::ImageSpec spec(width, height, channels, type);
        spec.attribute("oiio:UnassociatedAlpha", 1);
        EXPECT_TRUE(out->open(path, spec)) << out->geterror();
        EXPECT_TRUE(out->write_image(type, samples)) << out->geterror();
        out->close();
        std::ifstream in(path, std::ios::binary);
        return Bytes(std::istreambuf_iterator<char>(in), {});
    }
    std::string Save(const std::string& name, const std::string& bytes) const {
        const std::string path = (dir_ / name).string();
        GltfBuilder::Save(path, bytes);
        return path;
    }
    fs::path dir_;
};

uint32_t Rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a = 255) {
    return r | (g << 8) | (b << 16) | (a << 24);
}

std::vector<uint32_t> TexelsOf(const LoadedScene& loaded, size_t texture) {
    const Texture& t = loaded.scene.textures.at(texture);
    const auto first = loaded.scene.texels.begin() + std::ptrdiff_t(t.texelOffset);
    return std::vector<uint32_t>(first, first + std::ptrdiff_t(t.width) * t.height);
}

// stb's decoding through tinygltf's default loader, made texels as the importer makes them.
std::vector<uint32_t> StbTexels(const Bytes& encoded) {
    tinygltf::Image image;
    std::string err;
    EXPECT_TRUE(tinygltf::LoadImageData(&image, 0, &err, nullptr, 0, 0, encoded.data(),
                                        int(encoded.size()), nullptr))
        << err;
    const size_t bytes = size_t(image.bits / 8);
    std::vector<uint32_t> texels;
    for (size_t p = 0; p < image.image.size() / (4 * bytes); ++p) {
        auto high = [&](size_t c) {
            return uint32_t(image.image[(4 * p + c) * bytes + bytes - 1]);
        };
        texels.push_back(Rgba(high(0), high(1), high(2), high(3)));
    }
    return texels;
}

// The textured quad with its image as a data URI, an external file or a .glb buffer view.
enum class Container { kDataUri, kFile, kBufferView };

std::string QuadWithImage(const Bytes& image, const std::string& mimeType, Container container,
                          const std::string& fileName = "") {
    GltfBuilder b = test::TexturedQuadScene(kNearest, kClamp);
    switch (container) {
        case Container::kDataUri:
            b.doc["images"] = Json::array(
                {{{"uri", "data:" + mimeType + ";base64," + GltfBuilder::Base64(image)}}});
            return b.GltfText();
        case Container::kFile:
            b.doc["images"] = Json::array({{{"uri", fileName}}});
            return b.GltfText();
        case Container::kBufferView:
            while (b.bin.size() % 4) b.bin.push_back(0);
            b.doc["bufferViews"].push_back(
                {{"buffer", 0}, {"byteOffset", b.bin.size()}, {"byteLength", image.size()}});
            b.bin.insert(b.bin.end(), image.begin(), image.end());
            b.doc["images"] = Json::array(
                {{{"bufferView", b.doc["bufferViews"].size() - 1}, {"mimeType", mimeType}}});
            return b.Glb();
    }
    return "";
}

// tools/make_textured_gltf.py's 8x8 texture, a PNG data URI, shared by the asset's three
// textures.
TEST_F(GltfOiioTest, TexturedQuadsAssetDecodesToItsTexels) {
    const LoadedScene loaded = LoadSceneFile(test::SourcePath("assets/models/textured_quads.gltf"));
    std::vector<uint32_t> expected;
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x)
            expected.push_back((x + y) % 2 == 0
                                   ? Rgba((x * 37 + y * 11) % 256, 255 - x * 32, y * 32 + 16)
                                   : Rgba(240, 240 - 20 * y, 30 + 25 * x));
    ASSERT_EQ(loaded.scene.textures.size(), 3u);
    for (size_t t = 0; t < 3; ++t) {
        EXPECT_EQ(loaded.scene.textures[t].width, 8u);
        EXPECT_EQ(loaded.scene.textures[t].height, 8u);
        EXPECT_EQ(TexelsOf(loaded, t), expected) << "texture " << t;
    }
}

// Straight alpha included: OIIO's PNG reader would premultiply it unless told not to.
TEST_F(GltfOiioTest, PngReachesTheTexelsFromEveryContainer) {
    const int width = 5, height = 3;
    Bytes rgba;
    std::vector<uint32_t> expected;
    for (uint32_t i = 0; i < width * height; ++i) {
        const uint32_t r = 17 * i, g = 250 - 13 * i, b = (i * 91) % 256, a = i == 0 ? 0 : 18 * i;
        rgba.insert(rgba.end(), {uint8_t(r), uint8_t(g), uint8_t(b), uint8_t(a)});
        expected.push_back(Rgba(r, g, b, a));
    }
    const Bytes png = Encode("texture.png", width, height, 4, OIIO::TypeDesc::UINT8, rgba.data());
    EXPECT_EQ(StbTexels(png), expected) << "stb, the other builds' decoder, must agree";
    for (Container container : {Container::kDataUri, Container::kFile, Container::kBufferView}) {
        const std::string path =
            Save(container == Container::kBufferView ? "quad.glb" : "quad.gltf",
                 QuadWithImage(png, "image/png", container, "texture.png"));
        const LoadedScene loaded = LoadSceneFile(path);
        ASSERT_EQ(loaded.scene.textures.size(), 1u);
        EXPECT_EQ(loaded.scene.textures[0].width, uint32_t(width));
        EXPECT_EQ(TexelsOf(loaded, 0), expected) << "container " << int(container);
    }
}

// 16-bit samples keep their high byte and grey + alpha expands to RGBA, as with stb.
TEST_F(GltfOiioTest, PngChannelLayoutsExpandToRgba) {
    const std::vector<uint16_t> rgb16 = {0x1234, 0xabcd, 0xff00, 0x00ff, 0x8080, 0x7f7f};
    const Bytes wide = Encode("wide.png", 2, 1, 3, OIIO::TypeDesc::UINT16, rgb16.data());
    LoadedScene loaded =
        LoadSceneFile(Save("wide.gltf", QuadWithImage(wide, "image/png", Container::kDataUri)));
    const std::vector<uint32_t> wideTexels = {Rgba(0x12, 0xab, 0xff), Rgba(0x00, 0x80, 0x7f)};
    EXPECT_EQ(TexelsOf(loaded, 0), wideTexels);
    EXPECT_EQ(StbTexels(wide), wideTexels);
    const Bytes greyAlpha = {10, 200, 77, 0, 255, 128};
    const Bytes grey = Encode("grey.png", 3, 1, 2, OIIO::TypeDesc::UINT8, greyAlpha.data());
    loaded =
        LoadSceneFile(Save("grey.glb", QuadWithImage(grey, "image/png", Container::kBufferView)));
    const std::vector<uint32_t> greyTexels = {Rgba(10, 10, 10, 200), Rgba(77, 77, 77, 0),
                                              Rgba(255, 255, 255, 128)};
    EXPECT_EQ(TexelsOf(loaded, 0), greyTexels);
    EXPECT_EQ(StbTexels(grey), greyTexels);
}

TEST_F(GltfOiioTest, JpegIsDecodedByOpenImageIO) {
    const int size = 16;
    Bytes rgb;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            rgb.insert(rgb.end(), {uint8_t(x * 16), uint8_t(255 - y * 15), uint8_t(x * y * 7)});
    const Bytes jpeg = Encode("texture.jpg", size, size, 3, OIIO::TypeDesc::UINT8, rgb.data());
    // OIIO's own reading of the file, and stb's through tinygltf's default loader.
    Bytes oiio(rgb.size());
    auto in = OIIO::ImageInput::open((dir_ / "texture.jpg").string());
    ASSERT_TRUE(in) << OIIO::geterror();
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, oiio.data()));
    std::vector<uint32_t> expected;
    for (size_t p = 0; p < size_t(size * size); ++p)
        expected.push_back(Rgba(oiio[3 * p], oiio[3 * p + 1], oiio[3 * p + 2]));
    ASSERT_NE(StbTexels(jpeg), expected) << "this JPEG no longer tells the two decoders apart";
    for (Container container : {Container::kDataUri, Container::kBufferView}) {
        const LoadedScene loaded =
            LoadSceneFile(Save(container == Container::kBufferView ? "quad.glb" : "quad.gltf",
                               QuadWithImage(jpeg, "image/jpeg", container)));
        EXPECT_EQ(TexelsOf(loaded, 0), expected) << "container " << int(container);
    }
}

TEST_F(GltfOiioTest, UndecodableImageGivesOneErrorNamingIt) {
    const Bytes rgba(4 * 4 * 4, 200);
    const Bytes png = Encode("texture.png", 4, 4, 4, OIIO::TypeDesc::UINT8, rgba.data());
    struct Case {
        Bytes bytes;
        std::string reason;
    };
    const Case cases[] = {
        {Bytes(png.begin(), png.begin() + 40), "(png)"},
        {Bytes{'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'},
         "not a PNG, JPEG, BMP or GIF image (mimeType \"image/png\")"},
    };
    for (const Case& c : cases) {
        const std::string path =
            Save("bad.glb", QuadWithImage(c.bytes, "image/png", Container::kBufferView));
        ::testing::internal::CaptureStderr();
        try {
            LoadSceneFile(path);
            ADD_FAILURE() << c.reason << ": loaded without an error";
        } catch (const InputError& e) {
            EXPECT_EQ(e.Field(), "images[0]") << e.what();
            EXPECT_NE(e.Reason().find(c.reason), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
        // OIIO 2.4 keeps libpng's default error handler, which also prints its message.
        const std::string stderrText = ::testing::internal::GetCapturedStderr();
        EXPECT_TRUE(stderrText.empty() || stderrText.rfind("libpng error: ", 0) == 0) << stderrText;
    }
}

}  // namespace
}  // namespace rtrt
