// The accuracy benchmark's variants differ from the defaults where theory says they must, and
// only there: Moller-Trumbore lets rays through shared edges (Woop et al. 2013), the textbook
// sphere quadratic loses small far spheres (Haines et al. 2019), a fixed 1e-4 ray offset is
// too small far from the origin (pbrt-v4 6.8), and the double reference agrees with the float
// renderer on an easy scene.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "bench/accuracy/accuracy_policy.h"
#include "bench/accuracy/accuracy_renderer.h"
#include "bench/accuracy/image_metrics.h"
#include "engine/render_rt/pixel_sample.h"
#include "game/assets/procedural_shapes.h"

namespace rtrt {
namespace {

// A closed fan of 16 triangles around a vertex at an awkward position on a tilted plane; rays
// aimed at the centre vertex and at points of the shared spokes, from random points above.
// Exactly, every such ray hits the fan. Returns how many missed every triangle.
template <uint32_t kVariant>
int FanMisses() {
    const vec3 centre(0.1234567f, 0.7654321f, -0.3141593f);
    const vec3 u = glm::normalize(vec3(1.0f, 0.3f, 0.2f));
    const vec3 v = glm::normalize(glm::cross(vec3(0.1f, 0.2f, 1.0f), u));
    constexpr int kSpokes = 16;
    std::vector<vec3> ring;
    for (int i = 0; i < kSpokes; ++i) {
        const float a = 2.0f * kPi * float(i) / kSpokes;
        ring.push_back(centre + 0.37f * (std::cos(a) * u + std::sin(a) * v));
    }
    std::vector<Triangle> fan;
    for (int i = 0; i < kSpokes; ++i) fan.push_back({centre, ring[i], ring[(i + 1) % kSpokes]});
    const vec3 n = glm::normalize(glm::cross(u, v));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> r(-1.0f, 1.0f);
    int misses = 0;
    for (int k = 0; k < 4000; ++k) {
        const int spoke = k % kSpokes;
        const float along = k < 1000 ? 0.0f : 0.05f + 0.9f * (r(rng) * 0.5f + 0.5f);
        const vec3 target = centre + along * (ring[spoke] - centre);
        const vec3 origin = target + 2.0f * n + vec3(r(rng), r(rng), r(rng));
        Ray ray{origin, kInfinity, target - origin, 0.0f};
        const RaySetup setup = MakeRaySetup(ray);
        bool hit = false;
        for (const Triangle& t : fan) {
            TriangleHit h;
            hit = hit || AccuracyPolicy<kVariant>::IntersectTriangle(t, setup, kInfinity, &h);
        }
        misses += !hit;
    }
    return misses;
}

TEST(AccuracyVariants, MollerTrumboreLetsRaysThroughSharedEdgesWatertightDoesNot) {
    EXPECT_EQ(FanMisses<kAccuracyDefault>(), 0);
    EXPECT_GT(FanMisses<kAccuracyMollerTrumbore>(), 40);  // > 1% of the 4000 rays
}

// A sphere of radius 1, 10^4 from the ray origins: rays aimed inside its silhouette (at most
// 0.9 of the radius off the centre, so |l|^2 <= 0.81 r^2) must hit it, near the double t.
template <uint32_t kVariant>
int FarSphereFailures() {
    const Sphere s{vec3(0.3f, -0.2f, -1.0e4f), 1.0f};
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> r(-1.0f, 1.0f);
    int failures = 0;
    for (int k = 0; k < 2000; ++k) {
        vec2 off(r(rng), r(rng));
        if (glm::length(off) > 0.9f) off *= 0.9f / glm::length(off);
        const vec3 target = s.center + vec3(off, 0.0f);
        const Ray ray{vec3(0.0f), kInfinity, glm::normalize(target), 0.0f};
        // Nearest root in double: t = (b - sqrt(b^2 - a (|c|^2 - r^2))) / a, b = c.d, a = d.d
        // (the float direction is unit only to an ulp, which matters at t = 10^4).
        const glm::dvec3 c(s.center), d(ray.dir);
        const double a = glm::dot(d, d), b = glm::dot(c, d);
        const double expected = (b - std::sqrt(b * b - a * (glm::dot(c, c) - 1.0))) / a;
        float t;
        const bool hit = AccuracyPolicy<kVariant>::IntersectSphere(
            s, MakeSphereRay(ray.origin, ray.dir), kInfinity, &t);
        failures += !hit || std::abs(t - expected) > 0.01;
    }
    return failures;
}

TEST(AccuracyVariants, NaiveQuadraticLosesASmallFarSphereRtgFormDoesNot) {
    EXPECT_EQ(FarSphereFailures<kAccuracyDefault>(), 0);
    EXPECT_GT(FarSphereFailures<kAccuracyNaiveSphere>(), 200);  // > 10% of the 2000 rays
}

// Shadow rays leaving a surface far from the origin, toward a light above it: how many hit the
// surface they leave (acne). `scene` holds that surface alone.
template <uint32_t kVariant>
int SelfHits(const RenderScene& scene, vec3 eye, vec3 aim, vec3 spread, vec3 toLight) {
    using Policy = AccuracyPolicy<kVariant>;
    const RenderSceneView view = scene.HostView(1, 1, 1);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> r(-1.0f, 1.0f);
    int selfHits = 0, surfaceHits = 0;
    for (int k = 0; k < 2000; ++k) {
        const vec3 target = aim + spread * vec3(r(rng), r(rng), r(rng));
        SceneHit hit;
        if (!IntersectScene<Policy>(view.tlas, {eye, kInfinity, target - eye, 0.0f}, &hit))
            continue;
        ++surfaceHits;
        const Surface s = MakeSurface(view, {eye, kInfinity, target - eye, 0.0f}, hit);
        const Ray shadow = Policy::SpawnRay(s, toLight);
        selfHits += OccludedScene<Policy>(view.tlas, shadow);
    }
    EXPECT_GT(surfaceHits, 1000);
    return selfHits;
}

TEST(AccuracyVariants, FixedEpsilonShowsAcneOnAFarSphereErrorBoundsDoNot) {
    // A sphere of radius 100 centred 5 x 10^4 from the origin: its hit points err by ~10^-2.
    RenderScene scene;
    const vec3 centre(5e4f, 5e4f, 5e4f);
    const Sphere sphere{centre, 100.0f};
    scene.AddInstance(scene.AddBlas(std::make_shared<const Blas>(BuildSphereBlas({&sphere, 1}))),
                      scene.AddMaterial({}), glm::mat4(1.0f));
    scene.BuildTlas();
    const vec3 eye = centre + vec3(0.0f, 300.0f, 0.0f);
    const vec3 light = glm::normalize(vec3(0.3f, 1.0f, 0.2f));
    const vec3 spread(40.0f, 0.0f, 40.0f);
    EXPECT_EQ(SelfHits<kAccuracyDefault>(scene, eye, centre, spread, light), 0);
    EXPECT_GT(SelfHits<kAccuracyFixedEpsilon>(scene, eye, centre, spread, light), 100);
}

TEST(AccuracyVariants, FixedEpsilonWithMollerTrumboreShowsAcneOnAFarTiltedPlane) {
    // Two triangles with corners 10^5 from the origin, tilted (as the benchmark's ground): the
    // watertight test rejects the self-hits a fixed offset lets through (their t is within its
    // error bound of 0, and the plane test cannot tell their side either), so acne needs
    // Moller-Trumbore's t > 0 as well.
    TriangleMesh ground;
    const float h = 1e5f;
    for (vec2 c : {vec2(-h, -h), vec2(h, -h), vec2(h, h), vec2(-h, h)})
        ground.positions.push_back(vec3(c.x, 0.05f * c.x - 0.1f * c.y, c.y));
    ground.indices = {{0, 2, 1}, {0, 3, 2}};
    RenderScene scene;
    scene.AddInstance(scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(ground))),
                      scene.AddMaterial({}), glm::mat4(1.0f));
    scene.BuildTlas();
    const vec3 eye(0.0f, 10.0f, 10.0f), aim(0.0f, 0.0f, -10.0f), spread(8.0f, 0.0f, 8.0f);
    const vec3 light = glm::normalize(vec3(1.0f));
    constexpr uint32_t kTextbook = kAccuracyMollerTrumbore | kAccuracyFixedEpsilon;
    EXPECT_EQ(SelfHits<kAccuracyDefault>(scene, eye, aim, spread, light), 0);
    EXPECT_EQ(SelfHits<kAccuracyFloatOnly>(scene, eye, aim, spread, light), 0);
    EXPECT_EQ(SelfHits<kAccuracyFixedEpsilon>(scene, eye, aim, spread, light), 0);
    EXPECT_GT(SelfHits<kTextbook>(scene, eye, aim, spread, light), 100);
}

// An easy scene near the origin: a box and a reflective, a glass sphere, lit with shadows.
RenderScene EasyScene() {
    RenderScene scene;
    scene.camera = {vec3(0.0f, 1.0f, 8.0f), vec3(0.0f, -0.1f, -1.0f), vec3(0, 1, 0), 45.0f};
    scene.maxDepth = 6;
    Material red;
    red.diffuse = vec3(0.8f, 0.2f, 0.1f);
    red.specular = vec3(0.3f);
    red.reflectivity = 0.3f;
    Material glass;
    glass.diffuse = vec3(0.0f);
    glass.transmissivity = 0.9f;
    scene.AddInstance(scene.AddBlas(std::make_shared<const Blas>(
                          BuildTriangleBlas(MakeBoxMesh(vec3(2.0f, 1.0f, 1.5f))))),
                      scene.AddMaterial(red), glm::rotate(glm::mat4(1.0f), 0.4f, vec3(0, 1, 0)));
    const Sphere sphere{vec3(1.8f, 0.2f, 1.0f), 0.8f};
    scene.AddInstance(scene.AddBlas(std::make_shared<const Blas>(BuildSphereBlas({&sphere, 1}))),
                      scene.AddMaterial(glass), glm::mat4(1.0f));
    scene.lights.push_back(
        {glm::normalize(vec3(1.0f, 2.0f, 1.0f)), LightType::kDirectional, vec3(0.9f), 0.0f});
    scene.BuildTlas();
    return scene;
}

TEST(AccuracyReference, DoubleReferenceEqualsFloatWithinABoundOnAnEasyScene) {
    const RenderScene scene = EasyScene();
    RenderSettings settings;
    settings.width = 96;
    settings.height = 54;
    settings.maxDepth = scene.maxDepth;
    settings.samplesPerPixel = 4;
    Image image;
    RenderAccuracyCpu(scene, settings, kAccuracyDefault, image);
    const Image reference = RenderReference(scene, settings);
    const double rmse = Rmse(image, reference);
    EXPECT_GT(rmse, 0.0);   // computed apart: the reference is not the float path
    EXPECT_LT(rmse, 1e-5);  // but the same picture: float rounding only (2.7e-7 here)
    EXPECT_EQ(OutlierRate(image, reference, 0.1f), 0.0);
    EXPECT_EQ(MismatchRate(PrimaryObjectsCpu(scene, settings, kAccuracyDefault),
                           ReferencePrimaryObjects(scene, settings)),
              0.0);
}

TEST(AccuracyReference, DefaultVariantIsTheDefaultRendererBitForBit) {
    const RenderScene scene = EasyScene();
    RenderSettings settings;
    settings.width = 64;
    settings.height = 36;
    settings.maxDepth = scene.maxDepth;
    for (uint32_t spp : {1u, 4u}) {
        settings.samplesPerPixel = spp;
        Image image;
        RenderAccuracyCpu(scene, settings, kAccuracyDefault, image);
        EXPECT_EQ(image.pixels, RenderRaw(scene, settings).pixels) << spp << " spp";
    }
}

TEST(Supersampling, SamplesAreDeterministicOnePerStratumAndChangeTheImage) {
    for (uint32_t n : {2u, 3u, 4u}) {
        for (uint32_t s = 0; s < n * n; ++s) {
            const vec2 p = PixelSample(17, 5, s, n);
            EXPECT_EQ(p, PixelSample(17, 5, s, n));
            EXPECT_GE(p.x * float(n), float(s % n));
            EXPECT_LT(p.x * float(n), float(s % n + 1));
            EXPECT_GE(p.y * float(n), float(s / n));
            EXPECT_LT(p.y * float(n), float(s / n + 1));
        }
    }
    EXPECT_EQ(PixelSample(3, 4, 0, 1), vec2(0.5f));
    EXPECT_NE(PixelSample(3, 4, 0, 2), PixelSample(4, 3, 0, 2));  // jitter varies per pixel
    EXPECT_EQ(StrataPerSide(1), 1u);
    EXPECT_EQ(StrataPerSide(9), 3u);
    EXPECT_EQ(StrataPerSide(15), 3u);

    const RenderScene scene = EasyScene();
    RenderSettings settings;
    settings.width = 48;
    settings.height = 27;
    const Image one = RenderRaw(scene, settings);
    settings.samplesPerPixel = 9;
    const Image nine = RenderRaw(scene, settings);
    EXPECT_EQ(nine.pixels, RenderRaw(scene, settings).pixels);
    EXPECT_GT(Rmse(one, nine), 0.0);
}

}  // namespace
}  // namespace rtrt
