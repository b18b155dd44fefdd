#pragma once
// The fixture of the glTF import suites: a temporary folder per test, for the files it writes;
// and the check of a file that must be refused.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "engine/core/error.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"

namespace rtrt {

class GltfTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("rtrt_gltf_" + std::to_string(getpid()) + "_" + info->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string Save(const std::string& name, const std::string& bytes) const {
        const std::string path = (dir_ / name).string();
        test::GltfBuilder::Save(path, bytes);
        return path;
    }
    std::filesystem::path dir_;
};

// Loads PATH expecting one InputError naming FIELD and containing REASON.
inline void ExpectGltfError(const std::string& path, const std::string& field,
                            const std::string& reason) {
    try {
        LoadSceneFile(path);
        ADD_FAILURE() << path << ": loaded without an error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.File(), path);
        EXPECT_EQ(e.Field(), field) << e.what();
        EXPECT_NE(e.Reason().find(reason), std::string::npos) << e.what();
    }
}

}  // namespace rtrt
