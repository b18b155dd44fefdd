#include "game/assets/polygon_triangulation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

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
    // Corners at one place in a row count once, and a zero-width spike (out to a tip and back
    // along the same line: a corner whose neighbours coincide) covers nothing and is dropped with
    // its way back: either would leave no ear to clip.
    const auto at = [&](size_t k) { return corners[source_[k]]; };
    source_.clear();
    for (uint32_t i = 0; i < corners.size(); ++i) {
        if (!source_.empty() && corners[i] == at(source_.size() - 1)) continue;
        source_.push_back(i);
        while (source_.size() >= 3 && at(source_.size() - 1) == at(source_.size() - 3))
            source_.resize(source_.size() - 2);
    }
    for (bool dropped = true; dropped && source_.size() >= 3;) {
        const size_t last = source_.size() - 1;
        dropped = true;
        if (at(last) == at(0)) {
            source_.pop_back();
        } else if (at(last - 1) == at(0)) {  // the last corner is a tip
            source_.resize(last - 1);
        } else if (at(last) == at(1)) {  // the first corner is a tip
            source_.erase(source_.begin(), source_.begin() + 2);
        } else {
            dropped = false;
        }
    }
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
    // Lobes of opposite winding cancel in the Newell normal (a bowtie's is zero): such a polygon
    // is seen along the axis its corners spread least, so that a crossing still shows.
    glm::dvec3 absNormal = glm::abs(normal);
    const double largest = std::max({absNormal.x, absNormal.y, absNormal.z});
    if (!(largest > 0.0) || !std::isfinite(largest)) {
        glm::dvec3 lo(corners[source_[0]]), hi = lo;
        for (size_t i = 1; i < n; ++i) {
            lo = glm::min(lo, glm::dvec3(corners[source_[i]]));
            hi = glm::max(hi, glm::dvec3(corners[source_[i]]));
        }
        const glm::dvec3 spread = hi - lo;
        const int narrowest = spread.x <= spread.y && spread.x <= spread.z ? 0
                              : spread.y <= spread.z                       ? 1
                                                                           : 2;
        absNormal = glm::dvec3(0.0);
        absNormal[narrowest] = 1.0;
    }
    const int axis = absNormal.x >= absNormal.y && absNormal.x >= absNormal.z ? 0
                     : absNormal.y >= absNormal.z                             ? 1
                                                                              : 2;
    const double flip = normal[axis] < 0.0 ? -1.0 : 1.0;
    points_.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 p = glm::dvec3(corners[source_[i]]) - origin;
        points_[i] = glm::dvec2(p[(axis + 1) % 3], flip * p[(axis + 2) % 3]);
    }

    bool convex = true;
    for (size_t i = 0; convex && i < n; ++i)
        convex = Turn(points_[(i + n - 1) % n], points_[i], points_[(i + 1) % n]) >= 0.0;
    // One whose edges cross has no inside to keep: it is fanned, and counted for the warning. A
    // star drawn in one stroke turns one way at every corner, as a convex polygon does, but twice
    // round (a linear test); in others (a bowtie: ear clipping finds ears in both) edges are
    // tested in pairs.
    const bool hasArea = normal[axis] != 0.0 && std::isfinite(normal[axis]);
    const bool crosses =
        convex ? n >= 5 && hasArea && TurnsMoreThanOnce() : n >= 4 && CrossesItself();
    if (crosses) return FanAfterGivingUp(triangles, triangles.size(), noEar_);
    // A polygon with no area (its corners on a line) covers nothing: its fan is as good as any.
    if (convex || !hasArea) {
        for (size_t i = 2; i < n; ++i)
            triangles.emplace_back(source_[0], source_[i - 1], source_[i]);
        return;
    }
    const size_t firstTriangle = triangles.size();
    loops_.assign(1, {});
    for (uint32_t i = 0; i < n; ++i) loops_[0].push_back(i);
    if (!SplitAtTouchingCorners()) return FanAfterGivingUp(triangles, firstTriangle, overBudget_);
    for (size_t loop = 0; loop < loops_.size(); ++loop) {
        const Outcome outcome = ClipEars(loops_[loop], triangles);
        if (outcome == Outcome::kNoEar) return FanAfterGivingUp(triangles, firstTriangle, noEar_);
        if (outcome == Outcome::kOverBudget)
            return FanAfterGivingUp(triangles, firstTriangle, overBudget_);
    }
}

void PolygonTriangulator::FanAfterGivingUp(std::vector<glm::uvec3>& triangles, size_t firstTriangle,
                                           uint64_t& counter) {
    triangles.resize(firstTriangle);
    ++counter;
    for (size_t i = 2; i < source_.size(); ++i)
        triangles.emplace_back(source_[0], source_[i - 1], source_[i]);
}

// Whether the projected polygon, turning left at every corner, turns more than once round: the
// exterior angles of a convex polygon sum to 2 pi, a star's to 4 pi or more.
bool PolygonTriangulator::TurnsMoreThanOnce() const {
    const size_t n = points_.size();
    double turned = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 in = points_[i] - points_[(i + n - 1) % n];
        const glm::dvec2 out = points_[(i + 1) % n] - points_[i];
        turned += std::atan2(in.x * out.y - in.y * out.x, glm::dot(in, out));
    }
    return turned > 3.0 * 3.141592653589793;
}

// Whether two edges of the projected polygon that share no corner cross at a point inside both
// (touching, as at a pinch or along a slit, does not count). Quadratic in the corners: a polygon
// of more than 16 pays from a budget of its own (a file of small ones pays in its own size), and
// one it cannot pay for is not tested, leaving the ear tests' budget whole.
bool PolygonTriangulator::CrossesItself() {
    const size_t n = points_.size();
    if (n > 16) {
        const uint64_t work = uint64_t(n) * n / 2;
        if (crossingBudget_ < work) return false;
        crossingBudget_ -= work;
    }
    const auto side = [](double turn) { return (turn > 0.0) - (turn < 0.0); };
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 a = points_[i], b = points_[(i + 1) % n];
        for (size_t j = i + 2; j < n; ++j) {
            if ((j + 1) % n == i) continue;  // the edge before i shares corner i
            const glm::dvec2 c = points_[j], d = points_[(j + 1) % n];
            if (side(Turn(a, b, c)) * side(Turn(a, b, d)) < 0 &&
                side(Turn(c, d, a)) * side(Turn(c, d, b)) < 0)
                return true;
        }
    }
    return false;
}

bool PolygonTriangulator::Spend(uint64_t work) {
    if (budget_ < work) {
        budget_ = 0;
        return false;
    }
    budget_ -= work;
    return true;
}

// Twice the signed area of a loop of projected corners (the shoelace formula).
double PolygonTriangulator::LoopArea(std::span<const uint32_t> loop) const {
    double area = 0.0;
    for (size_t i = 0; i < loop.size(); ++i) {
        const glm::dvec2 a = points_[loop[i]], b = points_[loop[(i + 1) % loop.size()]];
        area += a.x * b.y - a.y * b.x;
    }
    return area;
}

// A polygon that touches itself at a corner (two lobes joined at one point, as exporters write
// a face with a pinch) is two loops, each counter-clockwise: they are clipped apart, since no
// ear test can tell which side of the shared point a triangle belongs to. A loop of the other
// winding at a repeated corner is a hole reached through a slit of zero width, and stays.
bool PolygonTriangulator::SplitAtTouchingCorners() {
    std::map<std::pair<double, double>, size_t> seen;  // a position's first place in the loop
    for (size_t loop = 0; loop < loops_.size(); ++loop) {
        bool split = true;
        while (split) {
            split = false;
            std::vector<uint32_t>& ring = loops_[loop];
            if (!Spend(ring.size())) return false;
            seen.clear();
            for (size_t j = 0; !split && j < ring.size(); ++j) {
                const glm::dvec2 p = points_[ring[j]];
                const auto [at, inserted] = seen.try_emplace({p.x, p.y}, j);
                if (inserted) continue;
                const size_t i = at->second;
                std::vector<uint32_t> inner(ring.begin() + i, ring.begin() + j);
                std::vector<uint32_t> outer(ring.begin() + j, ring.end());
                outer.insert(outer.end(), ring.begin(), ring.begin() + i);
                if (!(LoopArea(inner) > 0.0 && LoopArea(outer) > 0.0)) {
                    at->second = j;  // the later copy pairs with any that follows
                    continue;
                }
                ring = std::move(outer);
                loops_.push_back(std::move(inner));
                split = true;
            }
        }
    }
    return true;
}

// Ear clipping (Meisters 1975, "Polygons have ears"): a corner whose triangle with its two
// neighbours turns left and holds no other corner is cut off, until three remain. Only corners
// that do not turn left can lie in such a triangle of a simple polygon, so only they are tested;
// a corner at the same place as one of the triangle's is a slit's other side, and does not count.
PolygonTriangulator::Outcome PolygonTriangulator::ClipEars(std::span<const uint32_t> loop,
                                                           std::vector<glm::uvec3>& triangles) {
    const auto n = uint32_t(loop.size());
    if (n < 3) return Outcome::kDone;
    prev_.resize(n);
    next_.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        prev_[i] = (i + n - 1) % n;
        next_[i] = (i + 1) % n;
    }
    const auto at = [&](uint32_t i) { return points_[loop[i]]; };
    // Corners are reflex (or straight) by the current ring: clipping a neighbour can change it.
    const auto notConvex = [&](uint32_t i) {
        return Turn(at(prev_[i]), at(i), at(next_[i])) <= 0.0;
    };
    const auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
        triangles.emplace_back(source_[loop[a]], source_[loop[b]], source_[loop[c]]);
    };
    uint32_t remaining = n, cursor = 1 % n, failures = 0;
    while (remaining > 3) {
        if (!Spend(1)) return Outcome::kOverBudget;
        const uint32_t a = prev_[cursor], c = next_[cursor];
        const glm::dvec2 pa = at(a), pb = at(cursor), pc = at(c);
        bool ear = Turn(pa, pb, pc) > 0.0;
        for (uint32_t p = next_[c]; ear && p != a; p = next_[p]) {
            if (!Spend(1)) return Outcome::kOverBudget;
            const glm::dvec2 pp = at(p);
            if (pp == pa || pp == pb || pp == pc || !notConvex(p)) continue;
            ear = !InTriangle(pp, pa, pb, pc);
        }
        if (ear) {
            emit(a, cursor, c);
            next_[a] = c;
            prev_[c] = a;
            --remaining;
            cursor = c;
            failures = 0;
        } else {
            cursor = next_[cursor];
            if (++failures > remaining) return Outcome::kNoEar;
        }
    }
    // The last three turn left, or the loop had folded onto itself: no area is left to fill.
    if (Turn(at(prev_[cursor]), at(cursor), at(next_[cursor])) < 0.0) return Outcome::kNoEar;
    emit(prev_[cursor], cursor, next_[cursor]);
    return Outcome::kDone;
}

}  // namespace rtrt
