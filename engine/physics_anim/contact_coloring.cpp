#include "engine/physics_anim/contact_coloring.h"

namespace rtrt::physics {

void ContactColoring::Reset(uint32_t bodyCount) { used_.assign(bodyCount, 0); }

}  // namespace rtrt::physics
