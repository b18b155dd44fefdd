// Self-intersection seen in images: small scenes rendered with the CPU renderer, every pixel
// compared with what the geometry says, computed here in double without the tracer. Expected:
// zero wrong pixels. Shadow acne would darken lit pixels, a light leak would light dark ones, a
// mirror re-hitting itself would show its own colour instead of the background.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "engine/render_rt/renderer.h"
#include "tests/robust/closed_meshes.h"
#include "tests/robust/scene_builder.h"
#include "tests/robust/spawn_checks.h"

namespace rtrt::robust {
namespace {

constexpr uint32_t kWidth = 96, kHeight = 72;

Image Render(const RenderScene& scene, ViewMode view = ViewMode::kShaded) {
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.maxDepth = scene.maxDepth;
    s.view = view;
    return RenderRaw(scene, s);
}

Material Matte() {
    Material m;
    m.diffuse = vec3(0.8f);
    m.ambient = vec3(0.1f);
    return m;
}

// Lit colour of the matte material: ambient + diffuse n.l (no specular).
float LitValue(float nDotL) { return 0.1f + 0.8f * nDotL; }

// Ray/box in double: entry distance if the ray meets [lo, hi] at t > 0.
std::optional<double> HitBox(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi) {
    double t0 = 0, t1 = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return std::nullopt;
            continue;
        }
        double n = (lo[a] - o[a]) / d[a], f = (hi[a] - o[a]) / d[a];
        if (n > f) std::swap(n, f);
        t0 = std::max(t0, n);
        t1 = std::min(t1, f);
    }
    if (t0 > t1) return std::nullopt;
    return t0;
}

// A large plane far from the origin (its instance translated by d and tilted), lit by a
// directional light at 50 degrees; nothing else in the scene. Expected: every pixel that sees
// the plane has the lit value ambient + diffuse n.l of the plane's normal (to 1e-4, float
// shading), none is in shadow; the rest is background.
TEST(AcneAndLeaks, FarPlaneIsEvenlyLit) {
    for (float d : {1e3f, 1e4f, 1e5f}) {
        SCOPED_TRACE(d);
        RenderScene scene;
        scene.AddMaterial(Matte());
        const vec3 at = d * glm::normalize(vec3(1, -0.5f, 0.8f));
        const glm::mat4 place = Placement(at, 0.4f, vec3(1, 0, 1));
        scene.AddInstance(AddMeshBlas(scene, Quad(vec3(0), vec3(0, 1, 0))), 0, place);
        scene.BuildTlas();
        const vec3 n = glm::normalize(vec3(place * glm::vec4(0, 1, 0, 0)));
        const vec3 side = glm::normalize(glm::cross(n, vec3(1, 0, 0)));
        const vec3 l = std::cos(0.87f) * n + std::sin(0.87f) * side;
        scene.lights.push_back({l, LightType::kDirectional, vec3(1.0f), 0});
        scene.camera = {at + 3.0f * n + 0.5f * side, -n + 0.2f * side, side, 60.0f};
        const Image image = Render(scene);
        const float lit = LitValue(glm::dot(n, l));
        uint32_t planePixels = 0, wrong = 0;
        for (const vec3& c : image.pixels) {
            if (c == scene.background) continue;
            ++planePixels;
            wrong += std::abs(c.x - lit) > 1e-4f;
        }
        EXPECT_GT(planePixels, kWidth * kHeight / 2);
        EXPECT_EQ(wrong, 0u) << "of " << planePixels << " plane pixels; lit value " << lit;
    }
}

// A perfect mirror (reflectivity 1) far from the origin, alone in the scene. Expected: every
// pixel is the background, seen either directly or in the mirror (reflection weight 1, local 0).
TEST(AcneAndLeaks, FarMirrorShowsOnlyTheBackground) {
    for (float d : {1e3f, 1e4f, 1e5f}) {
        SCOPED_TRACE(d);
        RenderScene scene;
        Material mirror;
        mirror.reflectivity = 1.0f;
        scene.AddMaterial(mirror);
        const vec3 at = d * glm::normalize(vec3(-0.3f, 0.2f, 1.0f));
        const glm::mat4 place = Placement(at, 0.9f, vec3(0, 1, 1));
        scene.AddInstance(AddMeshBlas(scene, Quad(vec3(0), vec3(0, 1, 0))), 0, place);
        scene.maxDepth = 2;
        scene.BuildTlas();
        const vec3 n = glm::normalize(vec3(place * glm::vec4(0, 1, 0, 0)));
        scene.camera = {at + 4.0f * n + vec3(0.3f, 0, 0), -n, glm::cross(n, vec3(1, 0, 0)), 70.0f};
        const Image image = Render(scene);
        uint32_t wrong = 0;
        for (const vec3& c : image.pixels) wrong += glm::distance(c, scene.background) > 1e-5f;
        EXPECT_EQ(wrong, 0u);
        // The mirror is seen: a mirror lost at this distance would show the background too.
        const Image depth = Render(scene, ViewMode::kDepth);
        const auto mirrorPixels = std::count_if(depth.pixels.begin(), depth.pixels.end(),
                                                [](vec3 c) { return std::isfinite(c.x); });
        EXPECT_GT(mirrorPixels, kWidth * kHeight / 2);
    }
}

// A unit box standing on a floor, with gap 0 or 1e-4 under it, at the origin and 1e3 away,
// lit by a low light (elevation 25 degrees). Expected per floor pixel: in shadow exactly when the
// double-precision ray toward the light meets the box. Pixels whose answer changes when the box
// grows or shrinks by 1e-3 (rays grazing its edges, the floor under a 1e-4 gap) are ambiguous and
// skipped; all others must agree.
TEST(AcneAndLeaks, ContactShadowsUnderABoxHaveNoLeaks) {
    for (float far : {0.0f, 1e3f})
        for (float gap : {0.0f, 1e-4f}) {
            SCOPED_TRACE("at " + std::to_string(far) + ", gap " + std::to_string(gap));
            const vec3 origin(far, 0.5f * far, -far);
            RenderScene scene;
            scene.AddMaterial(Matte());
            TriangleMesh floor = Quad(vec3(0), vec3(0, 1, 0));
            scene.AddInstance(AddMeshBlas(scene, floor), 0, Placement(origin));
            const vec3 lo(-0.5f, gap, -0.5f), hi(0.5f, 1.0f + gap, 0.5f);
            scene.AddInstance(AddMeshBlas(scene, SubdividedBox(2, lo, hi).mesh), 0,
                              Placement(origin));
            const vec3 l = glm::normalize(vec3(std::cos(0.44f), std::sin(0.44f), 0.3f));
            scene.lights.push_back({l, LightType::kDirectional, vec3(1.0f), 0});
            scene.camera = {origin + vec3(-3.0f, 2.5f, 2.0f), vec3(2.0f, -2.5f, -2.0f),
                            vec3(0, 1, 0), 50.0f};
            scene.BuildTlas();
            const Image image = Render(scene);
            const CameraFrame frame = MakeCameraFrame(scene.camera, kWidth, kHeight);
            uint32_t checked = 0, shadowed = 0, wrong = 0;
            for (uint32_t y = 0; y < kHeight; ++y)
                for (uint32_t x = 0; x < kWidth; ++x) {
                    const Ray ray = PrimaryRay(frame, x, y, kWidth, kHeight);
                    const glm::dvec3 o = glm::dvec3(ray.origin) - glm::dvec3(origin);
                    const glm::dvec3 d(ray.dir);
                    if (d.y >= 0) continue;
                    const double tFloor = -o.y / d.y;
                    const glm::dvec3 p = o + tFloor * d;
                    if (std::abs(p.x) > 4.9 || std::abs(p.z) > 4.9) continue;
                    const glm::dvec3 grow(1e-3), blo(lo), bhi(hi);
                    if (HitBox(o, d, blo - grow, bhi + grow).value_or(1e300) < tFloor) continue;
                    const bool inShadowBig =
                        HitBox(p, glm::dvec3(l), blo - grow, bhi + grow).has_value();
                    const bool inShadowSmall =
                        HitBox(p, glm::dvec3(l), blo + grow, bhi - grow).has_value();
                    if (inShadowBig != inShadowSmall) continue;
                    ++checked;
                    shadowed += inShadowBig;
                    const bool renderedDark = image.At(x, y).x < 0.5f * (0.1f + LitValue(l.y));
                    wrong += renderedDark != inShadowBig;
                }
            EXPECT_GT(checked, kWidth * kHeight / 3);
            EXPECT_GT(shadowed, 100u);
            EXPECT_EQ(wrong, 0u) << "of " << checked << " floor pixels";
        }
}

// The camera inside a closed box room (inward faces, shared edges and corners), the light
// outside. Expected: no light gets in, so every pixel is the ambient value 0.1 exactly; a shadow
// ray slipping through a seam, a corner or its own wall would light a pixel. At the origin and
// 1e4 away. Exempt: pixels whose surface point lies within 4 float spacings of world coordinates
// (4 x 2^-23 x |p|: 5e-3 at 1e4, 1e-6 at the origin) of a second wall. A world-space ray origin
// is a float: rounding it (and offsetting it, which rounds each coordinate outward) moves it up
// to that far along the wall too, possibly behind the neighbouring wall. At most 1% of pixels.
TEST(AcneAndLeaks, ClosedRoomLetsNoLightIn) {
    for (float far : {0.0f, 1e4f}) {
        SCOPED_TRACE(far);
        const vec3 origin = far * glm::normalize(vec3(0.6f, -0.3f, 0.7f));
        RenderScene scene;
        scene.AddMaterial(Matte());
        const glm::mat4 place = Placement(origin, 0.3f, vec3(1, 1, 0));
        scene.AddInstance(AddMeshBlas(scene, SubdividedBox(4, vec3(-2), vec3(2)).mesh), 0, place);
        scene.lights.push_back(
            {glm::normalize(vec3(1, 1, 1)), LightType::kDirectional, vec3(1.0f), 0});
        scene.lights.push_back(
            {glm::normalize(vec3(-1, 0.2f, -0.5f)), LightType::kDirectional, vec3(1.0f), 0});
        scene.BuildTlas();
        const glm::dmat4 toObject = glm::inverse(glm::dmat4(place));
        const double band = 4.0 * 0x1p-23 * (double(glm::length(origin)) + 4.0);
        for (vec3 look : {vec3(-1, -1, -1), vec3(1, 0.2f, 0.1f), vec3(0.3f, 1, -1)}) {
            scene.camera = {origin + vec3(0.5f, 0.3f, 1.0f), look, vec3(0, 1, 0), 90.0f};
            const Image image = Render(scene);
            const CameraFrame frame = MakeCameraFrame(scene.camera, kWidth, kHeight);
            uint32_t lit = 0, exempt = 0;
            for (uint32_t y = 0; y < kHeight; ++y)
                for (uint32_t x = 0; x < kWidth; ++x) {
                    // Where the pixel's ray leaves the room [-2, 2]^3, in object space, in double.
                    const Ray ray = PrimaryRay(frame, x, y, kWidth, kHeight);
                    const glm::dvec3 o(toObject * glm::dvec4(glm::dvec3(ray.origin), 1.0));
                    const glm::dvec3 d(toObject * glm::dvec4(glm::dvec3(ray.dir), 0.0));
                    double t = 1e300;
                    for (int a = 0; a < 3; ++a)
                        t = std::min(t, ((d[a] > 0 ? 2.0 : -2.0) - o[a]) / d[a]);
                    const glm::dvec3 p = o + t * d;
                    // Distance to the nearest wall other than the one hit: the second-largest gap.
                    double gaps[3] = {2 - std::abs(p.x), 2 - std::abs(p.y), 2 - std::abs(p.z)};
                    std::sort(gaps, gaps + 3);
                    if (gaps[1] < band) {
                        ++exempt;
                        continue;
                    }
                    lit += std::abs(image.At(x, y).x - 0.1f) > 1e-6f;
                }
            EXPECT_EQ(lit, 0u) << "pixels lit inside the closed room";
            EXPECT_LE(exempt, kWidth * kHeight / 100);
        }
    }
}

// A huge ground sphere (radius 1e5 or 1e6, top at y = 0) with a unit box resting on its top,
// lit by a low light. Expected as for the floor above: every ground pixel dark exactly when the
// double-precision ray toward the light meets the box, pixels whose answer changes when the box
// grows or shrinks by 1e-3 skipped (the floor's margin: the sphere's points are placed in double,
// surface.h, so the ground is as exact as a plane).
TEST(AcneAndLeaks, BoxRestingOnAHugeGroundSphereCastsAnExactShadow) {
    for (const float radius : {1e5f, 1e6f}) {
        SCOPED_TRACE(radius);
        RenderScene scene;
        scene.AddMaterial(Matte());
        const Sphere ground{vec3(0), radius};
        scene.AddInstance(AddSphereBlas(scene, std::span(&ground, 1)), 0,
                          Placement(vec3(0, -radius, 0)));
        const vec3 lo(-0.5f, 0.0f, -0.5f), hi(0.5f, 1.0f, 0.5f);
        scene.AddInstance(AddMeshBlas(scene, SubdividedBox(2, lo, hi).mesh), 0, glm::mat4(1.0f));
        const vec3 l = glm::normalize(vec3(std::cos(0.44f), std::sin(0.44f), 0.3f));
        scene.lights.push_back({l, LightType::kDirectional, vec3(1.0f), 0});
        scene.camera = {vec3(-3.0f, 2.5f, 2.0f), vec3(2.0f, -2.5f, -2.0f), vec3(0, 1, 0), 50.0f};
        scene.BuildTlas();
        const Image image = Render(scene);
        const CameraFrame frame = MakeCameraFrame(scene.camera, kWidth, kHeight);
        const glm::dvec3 centre(0, -double(radius), 0);
        uint32_t checked = 0, shadowed = 0, wrong = 0;
        for (uint32_t y = 0; y < kHeight; ++y)
            for (uint32_t x = 0; x < kWidth; ++x) {
                const Ray ray = PrimaryRay(frame, x, y, kWidth, kHeight);
                const glm::dvec3 o(ray.origin), d(ray.dir);
                const glm::dvec3 f = o - centre;
                const double b = glm::dot(f, d), c = glm::dot(f, f) - double(radius) * radius;
                const double disc = b * b - c;
                if (disc < 0) continue;
                const double tGround = c / (-b + std::sqrt(disc));  // the near root, stably
                const glm::dvec3 p = o + tGround * d;
                const glm::dvec3 margin(1e-3), blo(lo), bhi(hi);
                if (HitBox(o, d, blo - margin, bhi + margin).value_or(1e300) < tGround) continue;
                const glm::dvec3 n = glm::normalize(p - centre);
                const bool big = HitBox(p, glm::dvec3(l), blo - margin, bhi + margin).has_value();
                const bool small = HitBox(p, glm::dvec3(l), blo + margin, bhi - margin).has_value();
                if (big != small) continue;
                ++checked;
                shadowed += big;
                const float litValue = LitValue(float(glm::dot(n, glm::dvec3(l))));
                const float value = image.At(x, y).x;
                wrong += big ? std::abs(value - 0.1f) > 1e-4f : std::abs(value - litValue) > 1e-3f;
            }
        EXPECT_GT(checked, kWidth * kHeight / 3);
        EXPECT_GT(shadowed, 100u);
        EXPECT_EQ(wrong, 0u) << "of " << checked << " ground pixels";
    }
}

}  // namespace
}  // namespace rtrt::robust
