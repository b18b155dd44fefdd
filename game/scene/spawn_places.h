#pragma once
// Where a scene file's spawners put their copies: the places of a "grid" or of a "rain".
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/math.h"
#include "game/scene/json_fields.h"

namespace rtrt {

// The places of the spawner F's "grid" ({count: [x, y, z], spacing}), centred on CENTRE.
std::vector<vec3> GridPlaces(JsonFields& f, vec3 centre, const std::string& file);

// The places of the spawner F's "rain" ({count, min, max, seed [DEFAULT_SEED]}) for bodies of
// radius BODY_RADIUS: jittered cells of a grid that fills [min, max], chosen in a seeded order,
// so places never overlap and a rain of bodies starts without interpenetration.
std::vector<vec3> RainPlaces(JsonFields& f, float bodyRadius, uint32_t defaultSeed,
                             const std::string& file);

}  // namespace rtrt
