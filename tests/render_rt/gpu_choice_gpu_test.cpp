// ChooseGpus (--gpus N|all) on a machine with CUDA devices: the present ones are taken, first
// ones first or all, and a count beyond them is refused naming how many there are. In the GPU
// suite, which the GPU machine runs (gpu_choice_test.cpp has the machine without one).
#include <gtest/gtest.h>

#include "engine/render_rt/render_settings.h"

namespace rtrt {
namespace {

TEST(ChooseGpusOnADevice, TakesTheFirstDevicesOrAll) {
    const uint32_t present = CudaDeviceCount();
    if (present == 0) GTEST_SKIP() << "no CUDA device here";
    std::vector<int> devices;
    std::string why;
    ASSERT_TRUE(ChooseGpus("1", &devices, &why)) << why;
    EXPECT_EQ(devices, std::vector<int>{0});
    ASSERT_TRUE(ChooseGpus("all", &devices, &why)) << why;
    ASSERT_EQ(devices.size(), present);
    for (uint32_t d = 0; d < present; ++d) EXPECT_EQ(devices[d], int(d));
}

TEST(ChooseGpusOnADevice, RefusesMoreThanThisMachineHas) {
    const uint32_t present = CudaDeviceCount();
    if (present == 0) GTEST_SKIP() << "no CUDA device here";
    std::vector<int> devices;
    std::string why;
    EXPECT_FALSE(ChooseGpus(std::to_string(present + 1), &devices, &why));
    EXPECT_NE(why.find("this machine has " + std::to_string(present) + " CUDA device"),
              std::string::npos)
        << why;
    EXPECT_NE(why.find("--gpus all"), std::string::npos) << why;
}

}  // namespace
}  // namespace rtrt
