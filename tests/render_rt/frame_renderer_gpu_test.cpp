// The frame-renderer checks of frame_renderer_checks.h on the CUDA back end, in the GPU suite
// (the unit suites, where the CPU back end runs them, are not run on the GPU machine).
#include <gtest/gtest.h>

#include "tests/render_rt/frame_renderer_checks.h"

namespace rtrt {
namespace {

TEST(CudaFrameRenderer, ShrunkSceneLeftAloneWhenUnchanged) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    test::ExpectShrunkSceneLeftAloneWhenUnchanged(Backend::kCuda);
}

}  // namespace
}  // namespace rtrt
