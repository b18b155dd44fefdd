// What the OBJ and PLY readers share (mesh_text.h).
#include "game/assets/mesh_text.h"

#include <gtest/gtest.h>

namespace rtrt {
namespace {

// The readers stop at kMaxTriangles, where a small file of long polygon fans would otherwise ask
// for tens of gigabytes.
TEST(MeshText, TriangleCountIsBounded) {
    EXPECT_NO_THROW(mesh_text::CheckTriangleCount(mesh_text::kMaxTriangles - 1));
    try {
        mesh_text::CheckTriangleCount(mesh_text::kMaxTriangles);
        ADD_FAILURE() << "no error at the bound";
    } catch (const mesh_text::RecordError& e) {
        EXPECT_EQ(e.reason, "over 134217728 triangles: more than rtrt takes in one mesh");
    }
}

}  // namespace
}  // namespace rtrt
