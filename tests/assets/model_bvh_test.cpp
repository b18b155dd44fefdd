// BVHs over the real models (fetched by tools/fetch_models.sh; skipped without them): well formed,
// shallow enough for the traversal stack, and traversed like brute force by every builder.
#include <gtest/gtest.h>

#include "engine/bvh/blas/blas.h"
#include "game/assets/mesh_io.h"
#include "game/assets/teapot.h"
#include "tests/bvh/tree_checks.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

TEST(ModelBvh, DragonBinnedTreeIsWellFormed) {
    RTRT_REQUIRE_MODEL(path, "dragon_vrip_res2.ply.gz");
    const Blas blas = BuildTriangleBlas(LoadMesh(path));
    test::ExpectWellFormed(blas);
    EXPECT_LT(ComputeStats(blas.nodes).maxDepth, kBvhStackSize);
}

class ModelTraversal : public test::EveryBuilder {};

TEST_P(ModelTraversal, DragonRes4MatchesBruteForce) {
    RTRT_REQUIRE_MODEL(path, "dragon_vrip_res4.ply.gz");
    test::ExpectMatchesBruteForce(BuildTriangleBlas(LoadMesh(path), Options()), 14);
}

TEST_P(ModelTraversal, TeapotMatchesBruteForce) {
    RTRT_REQUIRE_MODEL(path, "teapot.inc");
    test::ExpectMatchesBruteForce(BuildTriangleBlas(TessellateTeapot(path, 6), Options()), 15);
}

INSTANTIATE_TEST_SUITE_P(Builders, ModelTraversal, test::kAllBuilders, test::BuilderTestName);

}  // namespace
}  // namespace rtrt
