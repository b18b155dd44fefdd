// ChooseGpus (--gpus N|all): clear refusals of what is not a count, and of every count on a
// machine without a device (CI); gpu_choice_gpu_test.cpp checks a machine with one.
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

// With a device, gpu_choice_gpu_test.cpp in the GPU suite, which the GPU machine runs.
TEST(ChooseGpus, WithoutADeviceRefusesEveryCount) {
    if (CudaDeviceCount() > 0) GTEST_SKIP() << "a CUDA device is present";
    std::vector<int> devices;
    std::string why;
    EXPECT_FALSE(ChooseGpus("1", &devices, &why));
    EXPECT_EQ(why,
              "this machine has no usable CUDA device; leave out --gpus to render on the CPU "
              "back end");
    EXPECT_FALSE(ChooseGpus("all", &devices, &why));
}

}  // namespace
}  // namespace rtrt
