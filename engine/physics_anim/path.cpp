#include "engine/physics_anim/path.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace rtrt::physics {

namespace {
constexpr size_t kSplineSamples = 32;
}

Path::Path(std::vector<vec3> points, PathKind kind, bool closed)
    : points_(std::move(points)), kind_(kind), closed_(closed) {
    if (points_.size() < 2) {
        throw std::invalid_argument("Path: needs at least 2 points, got " +
                                    std::to_string(points_.size()));
    }
    for (size_t i = 0; i < points_.size(); ++i) {
        const vec3& p = points_[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            throw std::invalid_argument("Path: point " + std::to_string(i) + " is not finite");
        }
    }
    segmentCount_ = closed_ ? points_.size() : points_.size() - 1;
    samplesPerSegment_ = kind_ == PathKind::kPolyline ? 1 : kSplineSamples;
    const size_t samples = segmentCount_ * samplesPerSegment_;
    table_.resize(samples + 1);
    table_[0] = 0.0f;
    vec3 previous = points_[0];
    for (size_t i = 1; i <= samples; ++i) {
        const size_t segment = (i - 1) / samplesPerSegment_;
        const size_t k = i - segment * samplesPerSegment_;
        const vec3 p = SegmentPoint(segment, static_cast<float>(k) / samplesPerSegment_);
        table_[i] = table_[i - 1] + glm::length(p - previous);
        previous = p;
    }
}

vec3 Path::PointAt(float distance) const {
    const float length = Length();
    if (length <= 0.0f) return points_[0];
    if (closed_) {
        distance = std::fmod(distance, length);
        if (distance < 0.0f) distance += length;
    } else {
        distance = std::clamp(distance, 0.0f, length);
    }
    const size_t last = table_.size() - 2;  // the last sample interval
    const size_t i =
        std::min(static_cast<size_t>(std::upper_bound(table_.begin(), table_.end(), distance) -
                                     table_.begin()) -
                     1,
                 last);
    const float span = table_[i + 1] - table_[i];
    const float f = span > 0.0f ? std::min((distance - table_[i]) / span, 1.0f) : 0.0f;
    const size_t segment = i / samplesPerSegment_;
    const float u = (static_cast<float>(i - segment * samplesPerSegment_) + f) / samplesPerSegment_;
    return SegmentPoint(segment, u);
}

vec3 Path::SegmentPoint(size_t segment, float u) const {
    const auto s = static_cast<ptrdiff_t>(segment);
    const vec3& p1 = Point(s);
    const vec3& p2 = Point(s + 1);
    if (u <= 0.0f) return p1;
    if (u >= 1.0f) return p2;
    if (kind_ == PathKind::kPolyline) return glm::mix(p1, p2, u);
    // Catmull & Rom 1974, uniform: the tangent at a point is half the difference of its neighbours.
    const vec3& p0 = Point(s - 1);
    const vec3& p3 = Point(s + 2);
    const float u2 = u * u;
    const float u3 = u2 * u;
    return 0.5f * (2.0f * p1 + (p2 - p0) * u + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * u2 +
                   (3.0f * p1 - p0 - 3.0f * p2 + p3) * u3);
}

const vec3& Path::Point(ptrdiff_t i) const {
    const auto n = static_cast<ptrdiff_t>(points_.size());
    if (closed_) return points_[static_cast<size_t>(((i % n) + n) % n)];
    return points_[static_cast<size_t>(std::clamp<ptrdiff_t>(i, 0, n - 1))];
}

}  // namespace rtrt::physics
