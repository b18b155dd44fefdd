#pragma once
// A row of the contact passes: eight contacts of eight different manifolds of one colour, one per
// lane (lanes.h), laid out by ContactRows (contact_rows.h).
#include <cstdint>

#include "engine/physics_anim/lanes.h"

namespace rtrt::physics {

// Eight contacts of eight different manifolds of one colour. A lane without a contact (bit clear
// in activeLanes) has zero masses and impulses and the bodies of an active lane; it is never
// written back. The rows keep the contact points' offsets from the bodies and compute the lever
// arms: the passes stream the rows, and arms would make them half as large again.
struct ContactRow {
    uint32_t slotA[kLanes];
    uint32_t slotB[kLanes];
    uint32_t contact[kLanes];  // index in the step's contacts
    uint32_t activeLanes;      // bit per lane
    bool rolling;              // some lane has rolling resistance (RollingLanes)
    Lanes3 normal;
    Lanes3 tangent1;
    Lanes3 tangent2;
    Lanes3 anchorA;  // the contact point less body a's centre
    Lanes3 anchorB;
    Lanes normalMass;
    Lanes tangentMass1;
    Lanes tangentMass2;
    Lanes normalImpulse;
    Lanes tangentImpulse1;
    Lanes tangentImpulse2;
    Lanes friction;
    Lanes allowedApproach;  // speed at which a speculative contact may close: separation / dt
    Lanes bounce;           // the speed restitution leaves at (0: none)
    Lanes overlap;          // beyond the linear slop, for the position iterations
    Lanes pseudoImpulse;
};

// Rolling resistance of a row's lanes, apart: most rows have none and never read it.
struct RollingLanes {
    Lanes limit;
    Lanes3 impulse;
    Lanes33 mass;
};

}  // namespace rtrt::physics
