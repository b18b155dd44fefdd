// A spatial-split BLAS renders the paper scene as the binned BLAS of the same mesh does: the
// builders differ in which leaves hold a triangle, never in which triangle a ray hits first.
#include <gtest/gtest.h>

#include <memory>

#include "engine/render_rt/renderer.h"
#include "game/assets/teapot.h"
#include "game/scene/paper_scene.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

TEST(SpatialSplitBlas, RendersThePaperSceneAsTheBinnedBlas) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    const TriangleMesh mesh = TessellateTeapot(teapot, 6);
    BvhBuildOptions options;
    options.builder = BvhBuilder::kSpatialSah;
    auto spatial = std::make_shared<const Blas>(BuildTriangleBlas(mesh, options));
    auto binned = std::make_shared<const Blas>(BuildTriangleBlas(mesh));
    ASSERT_GT(spatial->PrimCount(), binned->PrimCount()) << "no triangle was split";

    RenderSettings s;
    s.width = 320;
    s.height = 240;
    s.maxDepth = kPaperMaxDepth;
    RenderStats binnedStats, spatialStats;
    const Image a = RenderRaw(MakePaperScene(binned), s, &binnedStats);
    const Image b = RenderRaw(MakePaperScene(spatial), s, &spatialStats);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    // Where a ray meets two triangles at the same t (a shared edge) either may be taken, and
    // their normals differ: a few pixels on edges may differ, nothing else.
    size_t differing = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i];
    EXPECT_LE(double(differing), 0.002 * double(a.pixels.size())) << differing << " pixels";
    EXPECT_NEAR(double(spatialStats.rays), double(binnedStats.rays), 0.001 * binnedStats.rays);
}

}  // namespace
}  // namespace rtrt
