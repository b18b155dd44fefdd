// Near contact on the CPU: rays starting 1e-5 from a surface, contact shadows 1e-5 under an
// occluder, small shadows on huge ground spheres (contact_checks.h).
#include "tests/robust/contact_checks.h"
#include "tests/robust/cpu_runner.h"

namespace rtrt::robust {
namespace {

TEST(Contact, RaysStartingNearASurfaceFindIt) { CheckRaysStartingNearASurfaceFindIt(CpuRunner{}); }
TEST(Contact, ContactShadowsAreDarkFromEveryLight) { CheckContactShadowsAreDark(CpuRunner{}); }
TEST(Contact, HugeGroundSpheresCastTheShadowsOfAPlane) {
    CheckSmallBoxShadowsOnGrounds(CpuRunner{});
}

}  // namespace
}  // namespace rtrt::robust
