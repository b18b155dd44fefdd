// Refraction: Snell's law and the exact Fresnel equations at known angles (closed form), total
// internal reflection, and in rendered images: index 1 makes an object vanish, nested dielectrics
// follow the documented model, a total-internal-reflection trap ends at the depth limit.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/render_rt/renderer.h"
#include "engine/render_rt/shading/optics.h"
#include "tests/robust/closed_meshes.h"
#include "tests/robust/scene_builder.h"

namespace rtrt::robust {
namespace {

// Fresnel reflectance of unpolarised light from index n1 into n2 at incidence thetaI, in double:
// Hecht, "Optics", 5th ed., eqs. 4.42-4.43 (r_s, r_p) and R = (r_s^2 + r_p^2) / 2.
double FresnelClosedForm(double thetaI, double n1, double n2) {
    const double sinT = n1 / n2 * std::sin(thetaI);
    if (sinT >= 1.0) return 1.0;
    const double cosI = std::cos(thetaI), cosT = std::sqrt(1.0 - sinT * sinT);
    const double rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
    const double rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

// Expected values (the closed form above, printed to 4 digits as a check of the formula itself):
// air to glass n = 1.5 at 0, 30, 45, 60, 80, 89 degrees: 0.0400, 0.0415, 0.0502, 0.0892, 0.3877,
// 0.9042; air to water n = 1.33 at 0 and 45 degrees: 0.0201, 0.0275; glass to air at 20, 30, 40
// degrees: 0.0417, 0.0552, 0.2453 (critical angle asin(1/1.5) = 41.81 degrees). Float tolerance:
// 2e-6 absolute.
TEST(Refraction, FresnelMatchesTheClosedFormAtKnownAngles) {
    struct Case {
        double degrees, n1, n2, published;
    };
    const Case cases[] = {{0, 1, 1.5, 0.0400},  {30, 1, 1.5, 0.0415},  {45, 1, 1.5, 0.0502},
                          {60, 1, 1.5, 0.0892}, {80, 1, 1.5, 0.3877},  {89, 1, 1.5, 0.9042},
                          {0, 1, 1.33, 0.0201}, {45, 1, 1.33, 0.0275}, {20, 1.5, 1, 0.0417},
                          {30, 1.5, 1, 0.0552}, {40, 1.5, 1, 0.2453}};
    for (const Case& c : cases) {
        const double theta = c.degrees * 3.14159265358979323846 / 180.0;
        const double exact = FresnelClosedForm(theta, c.n1, c.n2);
        EXPECT_NEAR(exact, c.published, 5e-5) << c.degrees;
        // FresnelDielectric takes eta = n_transmitted / n_incident; light from the far side is a
        // negative cosine with eta of the boundary seen from outside.
        const float f = c.n1 == 1 ? FresnelDielectric(float(std::cos(theta)), float(c.n2))
                                  : FresnelDielectric(-float(std::cos(theta)), float(c.n1));
        EXPECT_NEAR(f, exact, 2e-6) << c.degrees << " degrees, " << c.n1 << " -> " << c.n2;
    }
}

// At Brewster's angle tan(theta) = n the parallel term vanishes (Hecht 4.52): R = r_s^2 / 2 =
// 0.5 x 0.147929 for n = 1.5.
TEST(Refraction, FresnelAtBrewsterAngleIsHalfThePerpendicularTerm) {
    const float thetaB = std::atan(1.5f);
    EXPECT_NEAR(FresnelDielectric(std::cos(thetaB), 1.5f), 0.5f * 0.147929f, 1e-5f);
}

// Snell's law n1 sin(i) = n2 sin(t): 30, 45, 60 degrees into glass refract to 19.4712, 28.1255,
// 35.2644 degrees; the refracted direction is unit length and in the plane of incidence.
TEST(Refraction, RefractionFollowsSnellsLaw) {
    const float expectedDegrees[] = {19.4712206f, 28.1255057f, 35.2643897f};
    const float incident[] = {30.0f, 45.0f, 60.0f};
    for (int i = 0; i < 3; ++i) {
        const float thetaI = glm::radians(incident[i]);
        vec3 wt;
        ASSERT_TRUE(Refract(vec3(std::sin(thetaI), std::cos(thetaI), 0), vec3(0, 1, 0), 1.5f, &wt));
        EXPECT_NEAR(glm::degrees(std::asin(-wt.x)), expectedDegrees[i], 1e-4f);
        EXPECT_NEAR(wt.y, -std::cos(glm::radians(expectedDegrees[i])), 1e-6f);
        EXPECT_EQ(wt.z, 0.0f);
        EXPECT_NEAR(glm::length(wt), 1.0f, 1e-6f);
    }
}

// Inside glass (eta = 1/1.5) the critical angle is asin(1/1.5) = 41.81 degrees: beyond it
// Fresnel is 1 and Refract refuses, just below it light still gets out.
TEST(Refraction, TotalInternalReflectionBeyondTheCriticalAngle) {
    const float critical = std::asin(1.0f / 1.5f);
    EXPECT_EQ(FresnelDielectric(std::cos(critical + 0.01f), 1.0f / 1.5f), 1.0f);
    EXPECT_LT(FresnelDielectric(std::cos(critical - 0.01f), 1.0f / 1.5f), 1.0f);
    vec3 wt;
    const float a = critical + 0.01f;
    EXPECT_FALSE(Refract(vec3(std::sin(a), std::cos(a), 0), vec3(0, 1, 0), 1.0f / 1.5f, &wt));
    const float b = critical - 0.01f;
    EXPECT_TRUE(Refract(vec3(std::sin(b), std::cos(b), 0), vec3(0, 1, 0), 1.0f / 1.5f, &wt));
}

// Index 1: no reflection (F = 0 to 1e-12) and the ray goes straight on.
TEST(Refraction, IndexOneIsInvisibleToTheOptics) {
    EXPECT_NEAR(FresnelDielectric(0.3f, 1.0f), 0.0f, 1e-12f);
    vec3 wi = glm::normalize(vec3(0.3f, 0.8f, -0.1f)), wt;
    ASSERT_TRUE(Refract(wi, vec3(0, 1, 0), 1.0f, &wt));
    EXPECT_NEAR(glm::distance(wt, -wi), 0.0f, 1e-6f);
}

TEST(Refraction, ReflectMirrorsAboutTheNormal) {
    EXPECT_EQ(Reflect(glm::normalize(vec3(1, 1, 0)), vec3(0, 1, 0)),
              glm::normalize(vec3(-1, 1, 0)));
}

Material Glass(float ior) {
    Material m;
    m.diffuse = m.ambient = vec3(0.0f);
    m.transmissivity = 1.0f;
    m.ior = ior;
    return m;
}

Image RenderCpu(const RenderScene& scene, uint32_t w, uint32_t h, RenderStats* stats = nullptr) {
    RenderSettings s;
    s.width = w;
    s.height = h;
    s.maxDepth = scene.maxDepth;
    return RenderRaw(scene, s, stats);
}

// A glass ball of index 1 in front of coloured boxes and a wall. Expected: the image equals the
// image without the ball (every channel within 1e-4: refraction through index 1 is the identity,
// Fresnel is 1e-16). The light is placed so that the ball's shadow falls outside the view: the
// renderer's hard shadows treat every surface as opaque, glass included.
TEST(Refraction, IndexOneObjectVanishes) {
    RenderScene scene;
    Material wall;
    wall.diffuse = vec3(0.7f, 0.6f, 0.5f);
    scene.AddMaterial(wall);
    const vec3 colours[] = {vec3(0.9f, 0.1f, 0.1f), vec3(0.1f, 0.9f, 0.1f), vec3(0.1f, 0.1f, 0.9f)};
    for (vec3 c : colours) {
        Material m;
        m.diffuse = c;
        m.specular = vec3(0.3f);
        scene.AddMaterial(m);
    }
    const uint32_t glass = scene.AddMaterial(Glass(1.0f));
    scene.AddInstance(
        AddMeshBlas(scene, SubdividedBox(1, vec3(-8, -8, -5.1f), vec3(8, 8, -5)).mesh), 0,
        glm::mat4(1.0f));
    const uint32_t box = AddMeshBlas(scene, SubdividedBox(1, vec3(-0.5f), vec3(0.5f)).mesh);
    for (int i = 0; i < 3; ++i)
        scene.AddInstance(box, 1 + i,
                          Placement(vec3(-1.2f + 1.2f * i, 0.3f * i - 0.3f, -3), 0.5f * i + 0.2f,
                                    vec3(1, 0.7f, 0.3f)));
    scene.lights.push_back(
        {glm::normalize(vec3(0, 1, 0.2f)), LightType::kDirectional, vec3(1.0f), 0});
    // Generic rotations and an off-axis camera: no box edge may pass exactly through pixel
    // centres, where a 1e-6 shift of a ray through the ball would flip the pixel.
    scene.camera = {vec3(0.013f, 0.021f, 10), vec3(0, 0, -1), vec3(0, 1, 0), 30.0f};
    scene.maxDepth = 5;
    scene.BuildTlas();
    const Image without = RenderCpu(scene, 120, 90);
    const Sphere ball{vec3(0), 1.5f};
    scene.AddInstance(AddSphereBlas(scene, std::span(&ball, 1)), glass, glm::mat4(1.0f));
    scene.BuildTlas();
    const Image with = RenderCpu(scene, 120, 90);
    uint32_t differ = 0;
    for (size_t i = 0; i < with.pixels.size(); ++i) {
        const vec3 d = Abs(with.pixels[i] - without.pixels[i]);
        differ += MaxComponent(d) > 1e-4f;
    }
    EXPECT_EQ(differ, 0u);
}

// The camera inside a glass cube looking along (1, 1, 1) with a 10 degree field of view: every
// ray meets the faces at about 54.7 degrees (all direction cosines are below cos(41.81) = 0.745),
// beyond the critical angle, and reflects totally at every bounce, for ever. Expected: the path
// ends at the depth limit, each pixel having traced exactly maxDepth rays (no shadow rays: glass
// has no local term), and every pixel is exactly black (nothing but glass is ever seen).
TEST(Refraction, TotalInternalReflectionTrapEndsAtTheDepthLimit) {
    for (uint32_t depth : {2u, 8u, 16u}) {
        RenderScene scene;
        scene.AddMaterial(Glass(1.5f));
        scene.AddInstance(AddMeshBlas(scene, SubdividedBox(2, vec3(-1), vec3(1)).mesh), 0,
                          glm::mat4(1.0f));
        scene.lights.push_back(
            {glm::normalize(vec3(1, 2, 3)), LightType::kDirectional, vec3(1.0f), 0});
        scene.camera = {vec3(0.1f, -0.2f, 0.05f), vec3(1, 1, 1), vec3(0, 1, 0), 10.0f};
        scene.maxDepth = depth;
        scene.BuildTlas();
        RenderStats stats;
        const Image image = RenderCpu(scene, 33, 33, &stats);
        EXPECT_EQ(stats.rays, uint64_t(33 * 33) * depth) << "depth " << depth;
        uint32_t notBlack = 0;
        for (const vec3& c : image.pixels) notBlack += c != vec3(0.0f);
        EXPECT_EQ(notBlack, 0u) << "depth " << depth;
    }
}

// Along the axis through concentric balls, water (index 1.33, radius 2) around glass (1.5,
// radius 1), every boundary is met at normal incidence. The renderer's documented model treats
// each surface as a boundary between its material and air (README, "Shading": F is the Fresnel
// reflectance of a dielectric with index ior), so each crossing reflects F = ((n - 1)/(n + 1))^2
// of its own n and transmits 1 - F, and a path ends at maxDepth rays. Expected: the centre pixel
// equals the sum over all such paths along the axis, computed here in double (1e-5 relative);
// every pixel is finite and at most the background (weights never exceed 1).
double AxisRadiance(double z, double dir, uint32_t depth, uint32_t maxDepth) {
    struct Boundary {
        double z, n;
        bool outwardPlus;  // the sphere's outward normal at this point is +z
    };
    const Boundary boundaries[] = {
        {2, 1.33, true}, {1, 1.5, true}, {-1, 1.5, false}, {-2, 1.33, false}};
    const Boundary* next = nullptr;
    for (const Boundary& b : boundaries)
        if ((b.z - z) * dir > 1e-9 && (!next || std::abs(b.z - z) < std::abs(next->z - z)))
            next = &b;
    if (!next) return 1.0;              // background, in units of its value
    if (depth >= maxDepth) return 0.0;  // the last ray hit glass or water: no local term
    const double f = std::pow((next->n - 1.0) / (next->n + 1.0), 2.0);
    return f * AxisRadiance(next->z, -dir, depth + 1, maxDepth) +
           (1.0 - f) * AxisRadiance(next->z, dir, depth + 1, maxDepth);
}

TEST(Refraction, NestedDielectricsFollowTheSurfaceModelAlongTheAxis) {
    for (uint32_t maxDepth : {3u, 5u, 8u}) {
        RenderScene scene;
        const uint32_t water = scene.AddMaterial(Glass(1.33f));
        const uint32_t glass = scene.AddMaterial(Glass(1.5f));
        const Sphere outer{vec3(0), 2.0f}, inner{vec3(0), 1.0f};
        scene.AddInstance(AddSphereBlas(scene, std::span(&outer, 1)), water, glm::mat4(1.0f));
        scene.AddInstance(AddSphereBlas(scene, std::span(&inner, 1)), glass, glm::mat4(1.0f));
        scene.camera = {vec3(0, 0, 10), vec3(0, 0, -1), vec3(0, 1, 0), 20.0f};
        scene.maxDepth = maxDepth;
        scene.BuildTlas();
        const Image image = RenderCpu(scene, 33, 33);  // odd: the centre pixel's ray is the axis
        const double expected = AxisRadiance(10.0, -1.0, 1, maxDepth);
        const vec3 centre = image.At(16, 16);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(centre[c], expected * scene.background[c], 1e-5 * scene.background[c])
                << "max depth " << maxDepth;
        for (const vec3& p : image.pixels)
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(p[c]));
                ASSERT_LE(p[c], scene.background[c] * (1.0f + 1e-5f));
            }
    }
}

}  // namespace
}  // namespace rtrt::robust
