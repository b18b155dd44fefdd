#pragma once
// A test fixture with a folder of its own: made fresh for each test (named by the process and the
// test, so that suites run in parallel never share one) and removed after it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace rtrt::test {

class ScratchFolderTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("rtrt_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    // CONTENTS written byte for byte to NAME in the folder: its path.
    std::string Write(const std::string& name, const std::string& contents) const {
        const std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary | std::ios::trunc) << contents;
        return path;
    }

    std::filesystem::path dir_;
};

}  // namespace rtrt::test
