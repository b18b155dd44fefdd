#include "game/scene/spawn_places.h"

#include <algorithm>
#include <cstdint>
#include <random>

namespace rtrt {

std::vector<vec3> GridPlaces(JsonFields& f, vec3 centre, const std::string& file) {
    JsonFields g(f.Get("grid"), f.Path("grid"), file);
    const vec3 count = g.Vec3("count");
    const float spacing = g.Positive("spacing", 1.5f);
    g.Finish();
    if (count.x < 1 || count.y < 1 || count.z < 1 || count.x * count.y * count.z > 2e6f ||
        count != glm::floor(count))
        f.Fail("grid.count", "expected 3 whole numbers >= 1 (at most 2,000,000 places)");
    // The grid's corners are its farthest places: within the scene's bounds as a position must be
    // (a spacing of 1e20 put places at 1e20, where the objects vanished).
    const vec3 half = 0.5f * (count - vec3(1.0f));
    if (!(MaxComponent(glm::abs(centre) + spacing * half) <= kMaxSceneCoordinate))
        f.Fail("grid.spacing", "the grid's places would reach beyond 1e7 from the origin");
    std::vector<vec3> places;
    for (int z = 0; z < int(count.z); ++z)
        for (int y = 0; y < int(count.y); ++y)
            for (int x = 0; x < int(count.x); ++x)
                places.push_back(centre + spacing * (vec3(x, y, z) - half));
    return places;
}

std::vector<vec3> RainPlaces(JsonFields& f, float bodyRadius, uint32_t defaultSeed,
                             const std::string& file) {
    JsonFields r(f.Get("rain"), f.Path("rain"), file);
    const uint32_t count = r.Count("count", 1, 1000000, 100);
    const vec3 lo = r.Position("min"), hi = r.Position("max");
    const uint32_t seed = r.Count("seed", 0, UINT32_MAX - 1, defaultSeed);
    r.Finish();
    const float cell = 2.2f * bodyRadius;
    // Counted in doubles: tiny bodies in a large region make more cells than an int holds
    // (the conversion's overflow had said "holds only 0 bodies").
    const glm::dvec3 across = glm::floor(glm::dvec3(glm::max(hi - lo, vec3(0.0f))) / double(cell));
    const double cellCount = across.x * across.y * across.z;
    if (!(cellCount <= 50000000.0))
        f.Fail("rain", "the region is too large for bodies of this size (over 50M cells)");
    const glm::ivec3 cells(across);
    const int64_t total = int64_t(cells.x) * cells.y * cells.z;
    if (total < int64_t(count))
        f.Fail("rain", "the region holds only " + std::to_string(total) +
                           " bodies of this size, not " + std::to_string(count));
    std::vector<uint32_t> order(static_cast<size_t>(total));
    for (size_t i = 0; i < order.size(); ++i) order[i] = uint32_t(i);
    std::mt19937 rng(seed);
    std::shuffle(order.begin(), order.end(), rng);
    std::uniform_real_distribution<float> jitter(-1.0f, 1.0f);
    const float slack = 0.5f * (cell - 2.0f * bodyRadius);
    std::vector<vec3> places;
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t c = order[i];
        const vec3 index(float(c % cells.x), float((c / cells.x) % cells.y),
                         float(c / (cells.x * cells.y)));
        places.push_back(lo + cell * (index + vec3(0.5f)) +
                         slack * vec3(jitter(rng), jitter(rng), jitter(rng)));
    }
    return places;
}

}  // namespace rtrt
