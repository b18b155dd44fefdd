#pragma once
// A curve through control points, parameterised by arc length so that followers move at a speed.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/math.h"

namespace rtrt::physics {

enum class PathKind : uint8_t {
    kPolyline,    // straight segments between the points
    kCatmullRom,  // uniform Catmull-Rom spline through the points (C1)
};

// A closed path also runs from the last point back to the first, and distances wrap around it;
// on an open path they clamp to its ends. The spline's ends on an open path repeat the end point
// as the missing neighbour.
class Path {
  public:
    // Throws std::invalid_argument for fewer than two points or a non-finite point.
    Path(std::vector<vec3> points, PathKind kind, bool closed);

    float Length() const { return table_.back(); }
    bool Closed() const { return closed_; }
    // The point at arc length distance from the first point.
    vec3 PointAt(float distance) const;
    // The arc length at which the path passes control point i (i == point count: the end of a
    // closed path, back at point 0). PointAt(KnotDistance(i)) is point i.
    float KnotDistance(size_t i) const { return table_[i * samplesPerSegment_]; }

  private:
    vec3 SegmentPoint(size_t segment, float u) const;
    const vec3& Point(ptrdiff_t i) const;  // wraps (closed) or clamps (open)

    std::vector<vec3> points_;
    PathKind kind_;
    bool closed_;
    size_t segmentCount_;
    size_t samplesPerSegment_;
    // Arc length at each sample (segment s, sample k at index s * samplesPerSegment_ + k), with
    // the end of the path last. A spline's arc length is its chord length at 32 samples a segment.
    std::vector<float> table_;
};

}  // namespace rtrt::physics
