#include "game/assets/polygon_triangulation.h"

#include <cmath>

namespace rtrt {
namespace {

// Twice the signed area of the triangle (a, b, c): positive when it turns left.
double Turn(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    return (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
}

// Whether p lies in the left-turning triangle (a, b, c) or on its border.
bool InTriangle(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    return Turn(a, b, p) >= 0.0 && Turn(b, c, p) >= 0.0 && Turn(c, a, p) >= 0.0;
}

}  // namespace

void PolygonTriangulator::Triangulate(std::span<const vec3> corners,
                                      std::vector<glm::uvec3>& triangles) {
    source_.clear();
    for (uint32_t i = 0; i < corners.size(); ++i)
        if (source_.empty() || corners[i] != corners[source_.back()]) source_.push_back(i);
    while (source_.size() > 1 && corners[source_.back()] == corners[source_.front()])
        source_.pop_back();
    const size_t n = source_.size();
    if (n < 3) return;

    // Newell's normal: the sum of the edges' cross products, twice the polygon's vector area
    // whatever its shape. The plane drops its dominant axis; the other two, flipped where the
    // normal points down that axis, make the polygon wind counter-clockwise.
    const glm::dvec3 origin(corners[source_[0]]);
    glm::dvec3 normal(0.0);
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 a = glm::dvec3(corners[source_[i]]) - origin;
        const glm::dvec3 b = glm::dvec3(corners[source_[(i + 1) % n]]) - origin;
        normal += glm::cross(a, b);
    }
    const glm::dvec3 absNormal = glm::abs(normal);
    const int axis = absNormal.x >= absNormal.y && absNormal.x >= absNormal.z ? 0
                     : absNormal.y >= absNormal.z                             ? 1
                                                                              : 2;
    const double flip = normal[axis] < 0.0 ? -1.0 : 1.0;
    points_.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 p = glm::dvec3(corners[source_[i]]) - origin;
        points_[i] = glm::dvec2(p[(axis + 1) % 3], flip * p[(axis + 2) % 3]);
    }

    bool convex = normal[axis] != 0.0 && std::isfinite(normal[axis]);
    for (size_t i = 0; convex && i < n; ++i)
        convex = Turn(points_[(i + n - 1) % n], points_[i], points_[(i + 1) % n]) >= 0.0;
    if (convex || !ClipEars(triangles)) {
        for (size_t i = 2; i < n; ++i)
            triangles.emplace_back(source_[0], source_[i - 1], source_[i]);
    }
}

// Ear clipping (Meisters 1975, "Polygons have ears"): a corner whose triangle with its two
// neighbours turns left and holds no other corner is cut off, until three remain. Only corners
// that do not turn left can lie in such a triangle of a simple polygon, so only they are tested.
// False, with nothing appended, when the polygon has to be fanned instead.
bool PolygonTriangulator::ClipEars(std::vector<glm::uvec3>& triangles) {
    const uint32_t n = uint32_t(points_.size());
    prev_.resize(n);
    next_.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        prev_[i] = (i + n - 1) % n;
        next_[i] = (i + 1) % n;
    }
    const size_t firstTriangle = triangles.size();
    auto giveUp = [&](uint64_t& counter) {
        triangles.resize(firstTriangle);
        ++counter;
        return false;
    };
    // Corners are reflex (or straight) by the current ring: clipping a neighbour can change it.
    auto notConvex = [&](uint32_t i) {
        return Turn(points_[prev_[i]], points_[i], points_[next_[i]]) <= 0.0;
    };
    uint32_t remaining = n, cursor = 1, failures = 0;
    while (remaining > 3) {
        if (budget_ == 0) return giveUp(overBudget_);
        --budget_;
        const uint32_t a = prev_[cursor], c = next_[cursor];
        const glm::dvec2 pa = points_[a], pb = points_[cursor], pc = points_[c];
        bool ear = Turn(pa, pb, pc) > 0.0;
        for (uint32_t p = next_[c]; ear && p != a; p = next_[p]) {
            if (budget_ == 0) return giveUp(overBudget_);
            --budget_;
            const glm::dvec2 pp = points_[p];
            if (pp == pa || pp == pb || pp == pc || !notConvex(p)) continue;
            ear = !InTriangle(pp, pa, pb, pc);
        }
        if (ear) {
            triangles.emplace_back(source_[a], source_[cursor], source_[c]);
            next_[a] = c;
            prev_[c] = a;
            --remaining;
            cursor = c;
            failures = 0;
        } else {
            cursor = next_[cursor];
            if (++failures > remaining) return giveUp(noEar_);
        }
    }
    triangles.emplace_back(source_[prev_[cursor]], source_[cursor], source_[next_[cursor]]);
    return true;
}

}  // namespace rtrt
