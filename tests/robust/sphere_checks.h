#pragma once
// Ray/sphere hard cases (engine/geometry/sphere_intersect.h, Ray Tracing Gems ch. 7): small spheres
// far away, a huge ground sphere, origins inside. The expected t is the root of |o + t d - c|^2 =
// r^2 computed in double from the same float inputs (nearest root > 0), so it is exact to double
// precision. The float result must lie within a stated bound of it:
// - the stable form's error is a few ulps of the largest quantity it combines, max(|o - c|, r):
//   the hit point o + t d (in double) must lie within 16 ulps of that (16 * 2^-23 *
//   max(|o - c|, r)) of the sphere, measured along the normal (a grazing ray turns a small height
//   error into a large error in t), and t within 1% of the expected root. This is tight
//   for a small sphere far away (the textbook b^2 - 4ac form loses all digits there: with
//   r = 1e-5 |o - c|, b^2 and 4ac agree in their first 10 digits, float keeps 7);
// - rays aimed inside the disc (|offset| <= 0.9 r) hit and rays aimed outside (>= 1.1 r) miss.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "tests/robust/cases.h"

namespace rtrt::robust {

// Nearest root t > 0 in double, if any.
inline std::optional<double> SphereRootDouble(const Ray& ray, const Sphere& s) {
    const glm::dvec3 o(ray.origin), d(ray.dir), c(s.center);
    const glm::dvec3 f = o - c;
    const double a = glm::dot(d, d), b = glm::dot(f, d);
    const double cc = glm::dot(f, f) - double(s.radius) * double(s.radius);
    // Same stable form in double: disc from the closest point on the line.
    const glm::dvec3 l = f - (b / a) * d;
    const double disc = a * (double(s.radius) * s.radius - glm::dot(l, l));
    if (disc < 0) return std::nullopt;
    const double q = -b - std::copysign(std::sqrt(disc), b);
    double t0 = cc / q, t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > 0) return t0;
    if (t1 > 0) return t1;
    return std::nullopt;
}

struct NamedSphereCase {
    const char* why;
    SphereCase c;
    bool expectHit;
};

inline std::vector<NamedSphereCase> SphereCases() {
    std::vector<NamedSphereCase> cases;
    // Small spheres far away: radius 1e-5 of the distance (0.01 at 1e3 ... 1 at 1e5; 1/27 of a
    // pixel of a 4K image with a 60 degree field of view), rays from the origin aimed at points of
    // the sphere's silhouette disc at fractions of its radius. Float resolves the silhouette to
    // about an ulp of the distance (2^-23 D = 1.2% of r here), so 0.9 r must hit and 1.1 r miss.
    for (float dist : {1e3f, 1e4f, 1e5f})
        for (float frac : {0.0f, 0.5f, 0.9f, 1.1f, 1.5f}) {
            const Sphere s{vec3(0.3f * dist, -0.2f * dist, -dist), 1e-5f * dist};
            const vec3 toCentre = s.center;
            const vec3 side = glm::normalize(glm::cross(toCentre, vec3(0, 1, 0)));
            const vec3 aim = s.center + frac * s.radius * side;
            cases.push_back({"small sphere far away", {s, {vec3(0), kInfinity, aim, 0}}, frac < 1});
            // The same from a far origin 5 units before it on the same line: large |o|, small
            // |o - c|, and `side` still perpendicular to the ray.
            const vec3 o = s.center - 5.0f * glm::normalize(toCentre);
            cases.push_back(
                {"small sphere near a far origin", {s, {o, kInfinity, aim - o, 0}}, frac < 1});
        }
    // Huge ground spheres with their top at y = 0, seen from a camera 1.7 above it: the ground a
    // few units away must be hit, rays above the horizon must miss.
    for (float radius : {1e5f, 1e6f}) {
        const Sphere ground{vec3(0, -radius, 0), radius};
        for (float dz : {-1.0f, -3.0f, -10.0f, -100.0f})
            for (float dx : {0.0f, 0.7f, -4.0f})
                cases.push_back(
                    {"huge ground sphere, ray down to the ground",
                     {ground, {vec3(0.2f, 1.7f, 0.1f), kInfinity, vec3(dx, -1.7f, dz), 0}},
                     true});
        cases.push_back({"huge ground sphere, ray above the horizon",
                         {ground, {vec3(0, 1.7f, 0), kInfinity, vec3(0, 0.01f, -1), 0}},
                         false});
        // Straight down from 1.7 above the top: t = 1.7 exactly in real numbers.
        cases.push_back({"huge ground sphere, straight down",
                         {ground, {vec3(0, 1.7f, 0), kInfinity, vec3(0, -1, 0), 0}},
                         true});
    }
    // Origins inside: the hit is the far root.
    const Sphere unit{vec3(0.25f, -0.5f, 1.0f), 1.0f};
    for (vec3 offset : {vec3(0), vec3(0.5f, 0, 0), vec3(0, 0.999f, 0), vec3(0.3f, -0.4f, 0.5f)})
        for (vec3 d :
             {vec3(1, 0, 0), vec3(0, -1, 0), glm::normalize(vec3(1, 2, -3)), vec3(0, 1, 1e-3f)})
            cases.push_back(
                {"origin inside", {unit, {unit.center + offset, kInfinity, d, 0}}, true});
    const Sphere big{vec3(0), 1e4f};
    cases.push_back({"origin inside a huge sphere",
                     {big, {vec3(1, 2, 3), kInfinity, vec3(0.3f, -0.2f, 1.0f), 0}},
                     true});
    // Tangent rays: the line touches the sphere at one point (disc = 0); slightly inside hits.
    cases.push_back({"just inside tangent",
                     {unit, {unit.center + vec3(-5, 0.9999f, 0), kInfinity, vec3(1, 0, 0), 0}},
                     true});
    cases.push_back({"just outside tangent",
                     {unit, {unit.center + vec3(-5, 1.0001f, 0), kInfinity, vec3(1, 0, 0), 0}},
                     false});
    // Unnormalised directions (instance transforms scale them): t scales inversely.
    cases.push_back(
        {"long direction", {unit, {vec3(0.25f, -0.5f, -9), kInfinity, vec3(0, 0, 1e3f), 0}}, true});
    cases.push_back({"short direction",
                     {unit, {vec3(0.25f, -0.5f, -9), kInfinity, vec3(0, 0, 1e-3f), 0}},
                     true});
    return cases;
}

template <typename Runner>
void CheckSphereCases(const Runner& run) {
    SCOPED_TRACE(Runner::kName);
    const std::vector<NamedSphereCase> named = SphereCases();
    std::vector<SphereCase> cases;
    for (const NamedSphereCase& n : named) cases.push_back(n.c);
    const std::vector<PrimResult> got = run.Sphere(cases);
    for (size_t i = 0; i < named.size(); ++i) {
        const SphereCase& c = named[i].c;
        SCOPED_TRACE(std::string(named[i].why) + " #" + std::to_string(i));
        ASSERT_EQ(got[i].hit != 0, named[i].expectHit);
        const std::optional<double> exact = SphereRootDouble(c.ray, c.sphere);
        ASSERT_EQ(exact.has_value(), named[i].expectHit) << "the case's own expectation is wrong";
        if (!exact) continue;
        const glm::dvec3 o(c.ray.origin), d(c.ray.dir), centre(c.sphere.center);
        const double scale = std::max(glm::length(o - centre), double(c.sphere.radius));
        const glm::dvec3 p = o + double(got[i].t) * d;
        EXPECT_LE(std::abs(glm::length(p - centre) - c.sphere.radius), 16.0 * 0x1p-23 * scale)
            << "the hit point is off the surface";
        EXPECT_NEAR(got[i].t, *exact, 0.01 * *exact) << "not the expected root";
    }
}

}  // namespace rtrt::robust
