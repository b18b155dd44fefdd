#include "engine/physics_anim/narrow_phase.h"

#include <algorithm>
#include <cmath>

namespace rtrt::physics {

namespace {

// Keeps the part of a convex polygon with dot(normal, p) <= offset (Sutherland & Hodgman 1974).
struct Polygon {
    static constexpr int kCapacity = 16;
    vec3 points[kCapacity];
    int count = 0;
};

Polygon ClipPolygon(const Polygon& in, vec3 normal, float offset) {
    Polygon out;
    for (int i = 0; i < in.count; ++i) {
        const vec3& p = in.points[i];
        const vec3& q = in.points[(i + 1) % in.count];
        const float dp = glm::dot(normal, p) - offset;
        const float dq = glm::dot(normal, q) - offset;
        if (dp <= 0.0f && out.count < Polygon::kCapacity) out.points[out.count++] = p;
        if ((dp < 0.0f && dq > 0.0f) || (dp > 0.0f && dq < 0.0f)) {
            if (out.count < Polygon::kCapacity)
                out.points[out.count++] = p + (q - p) * (dp / (dp - dq));
        }
    }
    return out;
}

// Radius of the box's projection onto a unit axis.
float ProjectedRadius(const OrientedBox& box, vec3 axis) {
    return box.halfExtents.x * std::fabs(glm::dot(box.axes[0], axis)) +
           box.halfExtents.y * std::fabs(glm::dot(box.axes[1], axis)) +
           box.halfExtents.z * std::fabs(glm::dot(box.axes[2], axis));
}

// The reference face is ref's face along +-axis facing inc; the incident face is inc's face most
// opposed to it. flip says that ref is the second shape, so the normal must be reversed.
bool FaceContact(const OrientedBox& ref, const OrientedBox& inc, int axis, float margin, bool flip,
                 Manifold& out) {
    vec3 n = ref.axes[axis];
    if (glm::dot(inc.centre - ref.centre, n) < 0.0f) n = -n;

    int incAxis = 0;
    float best = -1.0f;
    for (int k = 0; k < 3; ++k) {
        const float d = std::fabs(glm::dot(inc.axes[k], n));
        if (d > best) {
            best = d;
            incAxis = k;
        }
    }
    const vec3 incNormal =
        glm::dot(inc.axes[incAxis], n) > 0.0f ? -inc.axes[incAxis] : inc.axes[incAxis];
    const vec3 faceCentre = inc.centre + incNormal * inc.halfExtents[incAxis];
    const int k1 = (incAxis + 1) % 3;
    const int k2 = (incAxis + 2) % 3;
    const vec3 u = inc.axes[k1] * inc.halfExtents[k1];
    const vec3 v = inc.axes[k2] * inc.halfExtents[k2];
    Polygon poly;
    poly.count = 4;
    poly.points[0] = faceCentre + u + v;
    poly.points[1] = faceCentre - u + v;
    poly.points[2] = faceCentre - u - v;
    poly.points[3] = faceCentre + u - v;

    for (const int side : {(axis + 1) % 3, (axis + 2) % 3}) {
        const vec3 s = ref.axes[side];
        const float centre = glm::dot(s, ref.centre);
        poly = ClipPolygon(poly, s, centre + ref.halfExtents[side]);
        poly = ClipPolygon(poly, -s, -centre + ref.halfExtents[side]);
    }

    const float faceOffset = glm::dot(n, ref.centre) + ref.halfExtents[axis];
    out.count = 0;
    out.normal = flip ? -n : n;
    for (int i = 0; i < poly.count; ++i) {
        const float separation = glm::dot(n, poly.points[i]) - faceOffset;
        if (separation <= margin) out.Add(poly.points[i] - 0.5f * separation * n, separation);
    }
    return out.count > 0;
}

// Ericson 2005, "Real-Time Collision Detection", 5.1.9: closest points of two segments, here
// given by centre, unit direction and half length.
void ClosestPointsOnSegments(vec3 ca, vec3 da, float ha, vec3 cb, vec3 db, float hb, vec3& pa,
                             vec3& pb) {
    const vec3 r = ca - cb;
    const float b = glm::dot(da, db);
    const float c = glm::dot(da, r);
    const float f = glm::dot(db, r);
    const float denom = 1.0f - b * b;
    float s = denom > 1e-6f ? std::clamp((b * f - c) / denom, -ha, ha) : 0.0f;
    const float t = std::clamp(f + s * b, -hb, hb);
    s = std::clamp(t * b - c, -ha, ha);
    pa = ca + da * s;
    pb = cb + db * t;
}

bool EdgeContact(const OrientedBox& a, int i, const OrientedBox& b, int j, vec3 n, Manifold& out) {
    // The edges along a's axis i and b's axis j that lie furthest towards each other.
    vec3 ca = a.centre;
    vec3 cb = b.centre;
    for (int k = 0; k < 3; ++k) {
        if (k != i)
            ca +=
                a.axes[k] * (glm::dot(a.axes[k], n) > 0.0f ? a.halfExtents[k] : -a.halfExtents[k]);
        if (k != j)
            cb +=
                b.axes[k] * (glm::dot(b.axes[k], n) > 0.0f ? -b.halfExtents[k] : b.halfExtents[k]);
    }
    vec3 pa;
    vec3 pb;
    ClosestPointsOnSegments(ca, a.axes[i], a.halfExtents[i], cb, b.axes[j], b.halfExtents[j], pa,
                            pb);
    out.count = 0;
    out.normal = n;
    out.Add(0.5f * (pa + pb), glm::dot(pb - pa, n));
    return true;
}

}  // namespace

bool CollideSpheres(vec3 centreA, float radiusA, vec3 centreB, float radiusB, float margin,
                    Manifold& out) {
    const vec3 d = centreB - centreA;
    const float distance = glm::length(d);
    const float separation = distance - radiusA - radiusB;
    if (separation > margin) return false;
    // Coincident centres have no direction between them: any normal separates them.
    out.normal = distance > 0.0f ? d / distance : vec3(0.0f, 1.0f, 0.0f);
    out.count = 0;
    out.Add(centreA + out.normal * (radiusA + 0.5f * separation), separation);
    return true;
}

bool CollideBoxSphere(const OrientedBox& box, vec3 centre, float radius, float margin,
                      Manifold& out) {
    const vec3 local = glm::transpose(box.axes) * (centre - box.centre);
    const vec3 clamped = glm::clamp(local, -box.halfExtents, box.halfExtents);
    vec3 normalLocal;
    vec3 surfaceLocal = clamped;
    float separation;
    if (clamped != local) {
        const vec3 d = local - clamped;
        const float distance = glm::length(d);
        separation = distance - radius;
        if (separation > margin) return false;
        normalLocal = d / distance;
    } else {
        // The centre is inside: leave through the nearest face.
        const vec3 depth = box.halfExtents - Abs(local);
        int k = 0;
        if (depth.y < depth[k]) k = 1;
        if (depth.z < depth[k]) k = 2;
        normalLocal = vec3(0.0f);
        normalLocal[k] = local[k] < 0.0f ? -1.0f : 1.0f;
        surfaceLocal[k] = normalLocal[k] * box.halfExtents[k];
        separation = -depth[k] - radius;
    }
    out.normal = box.axes * normalLocal;
    out.count = 0;
    const vec3 surface = box.centre + box.axes * surfaceLocal;
    out.Add(surface + 0.5f * separation * out.normal, separation);
    return true;
}

bool CollideBoxes(const OrientedBox& a, const OrientedBox& b, float margin, Manifold& out) {
    const vec3 d = b.centre - a.centre;
    float faceSeparation[2] = {-kInfinity, -kInfinity};
    int faceAxis[2] = {0, 0};
    const OrientedBox* boxes[2] = {&a, &b};
    for (int which = 0; which < 2; ++which) {
        const OrientedBox& self = *boxes[which];
        const OrientedBox& other = *boxes[1 - which];
        for (int k = 0; k < 3; ++k) {
            const vec3 axis = self.axes[k];
            const float s =
                std::fabs(glm::dot(d, axis)) - self.halfExtents[k] - ProjectedRadius(other, axis);
            if (s > margin) return false;
            if (s > faceSeparation[which]) {
                faceSeparation[which] = s;
                faceAxis[which] = k;
            }
        }
    }
    float edgeSeparation = -kInfinity;
    int edgeI = 0;
    int edgeJ = 0;
    vec3 edgeNormal(0.0f);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            vec3 axis = glm::cross(a.axes[i], b.axes[j]);
            const float length = glm::length(axis);
            if (length < 1e-4f) continue;  // parallel edges: the face axes cover this direction
            axis /= length;
            const float s =
                std::fabs(glm::dot(d, axis)) - ProjectedRadius(a, axis) - ProjectedRadius(b, axis);
            if (s > margin) return false;
            if (s > edgeSeparation) {
                edgeSeparation = s;
                edgeI = i;
                edgeJ = j;
                edgeNormal = glm::dot(d, axis) < 0.0f ? -axis : axis;
            }
        }
    }
    // Faces give stable multi-point manifolds, so an edge axis (or b's face) must separate clearly
    // better to be chosen; the tolerance keeps a resting box from flickering between features.
    constexpr float kTolerance = 0.005f;
    const float bestFace = std::max(faceSeparation[0], faceSeparation[1]);
    if (edgeSeparation > bestFace + kTolerance)
        return EdgeContact(a, edgeI, b, edgeJ, edgeNormal, out);
    if (faceSeparation[1] > faceSeparation[0] + kTolerance) {
        return FaceContact(b, a, faceAxis[1], margin, true, out);
    }
    return FaceContact(a, b, faceAxis[0], margin, false, out);
}

bool CollidePlaneSphere(const PlaneShape& plane, vec3 centre, float radius, float margin,
                        Manifold& out) {
    const float separation = glm::dot(plane.normal, centre) - plane.offset - radius;
    if (separation > margin) return false;
    out.normal = plane.normal;
    out.count = 0;
    out.Add(centre - plane.normal * (radius + 0.5f * separation), separation);
    return true;
}

bool CollidePlaneBox(const PlaneShape& plane, const OrientedBox& box, float margin, Manifold& out) {
    out.normal = plane.normal;
    out.count = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const vec3 sign((corner & 1) ? 1.0f : -1.0f, (corner & 2) ? 1.0f : -1.0f,
                        (corner & 4) ? 1.0f : -1.0f);
        const vec3 p = box.centre + box.axes * (sign * box.halfExtents);
        const float separation = glm::dot(plane.normal, p) - plane.offset;
        if (separation <= margin) out.Add(p - 0.5f * separation * plane.normal, separation);
    }
    return out.count > 0;
}

}  // namespace rtrt::physics
