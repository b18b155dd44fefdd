// ChooseGpus (--gpus N|all): counts this machine has, "all", and clear refusals of the rest. CI
// has no GPU, where every count is refused; on the GPU machine the present ones are accepted.
#include <gtest/gtest.h>

#include "engine/render_rt/render_settings.h"

namespace rtrt {
namespace {

TEST(ChooseGpus, RefusesWhatIsNotACount) {
    for (const char* text : {"", "0", "-1", "two", "2x", " 2", "1.5"}) {
        std::vector<int> devices{7};
        std::string why;
        EXPECT_FALSE(ChooseGpus(text, &devices, &why)) << text;
        EXPECT_NE(why.find("expected a number of GPUs"), std::string::npos) << why;
        EXPECT_EQ(devices, std::vector<int>{7}) << "untouched on refusal";
    }
}

TEST(ChooseGpus, RefusesMoreThanThisMachineHas) {
    const uint32_t present = CudaDeviceCount();
    std::vector<int> devices;
    std::string why;
    EXPECT_FALSE(ChooseGpus(std::to_string(present + 1), &devices, &why));
    if (present == 0) {
        EXPECT_EQ(why, "this machine has no usable CUDA device");
        EXPECT_FALSE(ChooseGpus("all", &devices, &why));
    } else {
        EXPECT_NE(why.find("this machine has " + std::to_string(present) + " CUDA device"),
                  std::string::npos)
            << why;
        EXPECT_NE(why.find("--gpus all"), std::string::npos) << why;
    }
}

TEST(ChooseGpus, TakesTheFirstDevicesOrAll) {
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

}  // namespace
}  // namespace rtrt
