// A scene file's colour convention: display values by default (the images rtrt always made),
// or "colours": "linear" with an exposure and a tone map, applied to 8-bit outputs only.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "engine/render_rt/renderer.h"
#include "game/assets/image_io.h"
#include "game/scene/scene_file.h"

namespace rtrt {
namespace {

// One sphere far below the view: every pixel is the background.
std::string BackgroundScene(const std::string& extra) {
    return R"({"background": [0.5, 0.25, 2.0], )" + extra + R"(
      "models": {"ball": {"type": "sphere", "radius": 1}},
      "instances": [{"model": "ball", "position": [0, -1000, 0]}]})";
}

std::string ErrorOf(const std::string& json) {
    try {
        ParseScene(json, "s.json", "");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(SceneOutputTransform, DisplayColoursByDefault) {
    const LoadedScene s = ParseScene(BackgroundScene(""), "s.json", "");
    EXPECT_EQ(s.output.toneMap, ToneMap::kClamp);
    EXPECT_EQ(s.output.srgbEncode, 0u);
    EXPECT_EQ(s.output.exposureEv, 0.0f);
}

TEST(SceneOutputTransform, LinearColoursTakeExposureAndToneMap) {
    const LoadedScene s =
        ParseScene(BackgroundScene(R"("colours": "linear", "exposure": -1.5, "tone_map": "aces",)"),
                   "s.json", "");
    EXPECT_EQ(s.output.toneMap, ToneMap::kAces);
    EXPECT_EQ(s.output.srgbEncode, 1u);
    EXPECT_EQ(s.output.exposureEv, -1.5f);
    const LoadedScene d = ParseScene(BackgroundScene(R"("colours": "linear",)"), "s.json", "");
    EXPECT_EQ(d.output.toneMap, ToneMap::kPbrNeutral);
}

TEST(SceneOutputTransform, BadValuesNameTheField) {
    EXPECT_NE(ErrorOf(BackgroundScene(R"("colours": "srgb",)"))
                  .find("s.json: colours: expected \"display\" or \"linear\""),
              std::string::npos);
    EXPECT_NE(ErrorOf(BackgroundScene(R"("exposure": 1,)"))
                  .find("s.json: exposure: applies to linear colours"),
              std::string::npos);
    EXPECT_NE(ErrorOf(BackgroundScene(R"("colours": "linear", "tone_map": "filmic",)"))
                  .find("s.json: tone_map: expected pbr_neutral, aces or clamp"),
              std::string::npos);
    EXPECT_NE(ErrorOf(BackgroundScene(R"("colours": "linear", "exposure": 40,)")).find("exposure"),
              std::string::npos);
}

// The background's linear (0.5, 0.25, 2.0) through exposure -1 (0.25, 0.125, 1.0), PBR Neutral
// (offset 0.04, then the peak 0.96 compressed) and sRGB, into an 8-bit PPM; a PFM keeps 0.5.
TEST(SceneOutputTransform, EightBitOutputsAreTransformedAndFloatOutputsStayLinear) {
    const LoadedScene s =
        ParseScene(BackgroundScene(R"("colours": "linear", "exposure": -1,)"), "s.json", "");
    RenderSettings settings;
    settings.width = 8;
    settings.height = 4;
    const Image raw = RenderRaw(s.scene, settings);
    ASSERT_EQ(raw.At(3, 2).x, 0.5f);
    const vec3 display = ApplyOutputTransform(raw.At(3, 2), s.output);
    const vec3 expected = PbrNeutral(vec3(0.25f, 0.125f, 1.0f));
    EXPECT_FLOAT_EQ(display.x, SrgbEncode(expected.x));
    EXPECT_FLOAT_EQ(display.z, SrgbEncode(expected.z));
    EXPECT_LT(expected.z, 1.0f);  // the blue channel is compressed, not clipped

    const std::string dir = testing::TempDir();
    WriteImage(dir + "/linear.ppm", raw, s.output);
    WriteImage(dir + "/linear.pfm", raw, s.output);
    std::ifstream ppm(dir + "/linear.ppm", std::ios::binary);
    std::string header;
    for (int lines = 0; lines < 3; ++lines) {
        std::string line;
        std::getline(ppm, line);
        header += line;
    }
    unsigned char rgb[3];
    ppm.read(reinterpret_cast<char*>(rgb), 3);
    EXPECT_EQ(rgb[0], DisplayByte(SrgbEncode(expected.x)));
    EXPECT_EQ(rgb[1], DisplayByte(SrgbEncode(expected.y)));
    EXPECT_EQ(rgb[2], DisplayByte(SrgbEncode(expected.z)));
    std::ifstream pfm(dir + "/linear.pfm", std::ios::binary);
    std::string line;
    for (int lines = 0; lines < 3; ++lines) std::getline(pfm, line);
    float first[3];
    pfm.read(reinterpret_cast<char*>(first), sizeof(first));
    EXPECT_EQ(first[0], 0.5f);
    EXPECT_EQ(first[1], 0.25f);
    EXPECT_EQ(first[2], 2.0f);
}

}  // namespace
}  // namespace rtrt
