#pragma once
// Contact generation for each pair of shapes: where two shapes touch or, within a margin, are
// about to (speculative contacts, which stop fast bodies at the surface instead of tunnelling).
#include <glm/mat3x3.hpp>

#include "engine/core/math.h"

namespace rtrt::physics {

struct ContactPoint {
    vec3 point;        // world space, halfway between the two surfaces
    float separation;  // gap along the normal; negative when the shapes overlap
};

// Up to 8 points sharing one normal, which points from the first shape to the second.
struct Manifold {
    static constexpr int kMaxPoints = 8;
    vec3 normal{0.0f, 1.0f, 0.0f};
    int count = 0;
    ContactPoint points[kMaxPoints];

    void Add(vec3 point, float separation) {
        if (count < kMaxPoints) points[count++] = {point, separation};
    }
};

struct OrientedBox {
    vec3 centre;
    glm::mat3 axes;  // columns: the box's local x, y, z in world space
    vec3 halfExtents;
};

// The plane dot(normal, x) = offset with unit normal; the solid side is behind it.
struct PlaneShape {
    vec3 normal;
    float offset;
};

// Each returns true and fills out when the shapes are closer than margin (separation <= margin),
// with the normal pointing from the first argument to the second.
bool CollideSpheres(vec3 centreA, float radiusA, vec3 centreB, float radiusB, float margin,
                    Manifold& out);
bool CollideBoxSphere(const OrientedBox& box, vec3 centre, float radius, float margin,
                      Manifold& out);
// Separating axis test over the 15 axes (Gottschalk et al. 1996, "OBBTree"); a face axis gives the
// incident face clipped against the reference face's sides (Sutherland-Hodgman), an edge axis the
// closest points of the two edges (Gregorius 2013, "The Separating Axis Test between Convex
// Polyhedra").
bool CollideBoxes(const OrientedBox& a, const OrientedBox& b, float margin, Manifold& out);
bool CollidePlaneSphere(const PlaneShape& plane, vec3 centre, float radius, float margin,
                        Manifold& out);
// One point per box corner within margin of the plane.
bool CollidePlaneBox(const PlaneShape& plane, const OrientedBox& box, float margin, Manifold& out);

}  // namespace rtrt::physics
