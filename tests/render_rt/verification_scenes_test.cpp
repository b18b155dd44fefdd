// The paper's verification scenes (assets/scenes/), checked for what a person would check by eye,
// against analytic expectations computed here independently of the tracer.
#include <gtest/gtest.h>

#include <optional>

#include "engine/geometry/triangle_intersect.h"
#include "engine/render_rt/renderer.h"
#include "game/scene/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

LoadedScene LoadAsset(const std::string& name) {
    return LoadSceneFile(test::SourcePath("assets/scenes/" + name));
}

Image RenderCpu(const RenderScene& scene, uint32_t w, uint32_t h,
                ViewMode view = ViewMode::kShaded) {
    RenderSettings s;
    s.width = w;
    s.height = h;
    s.maxDepth = scene.maxDepth;
    s.view = view;
    return RenderRaw(scene, s);
}

// Analytic ray/sphere: nearest t > 0, if any.
std::optional<float> HitSphere(vec3 o, vec3 d, vec3 c, float r) {
    const vec3 f = o - c;
    const double b = glm::dot(f, d), cc = double(glm::dot(f, f)) - double(r) * r;
    const double disc = b * b - cc;  // d is unit length
    if (disc < 0) return std::nullopt;
    const double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
    if (t0 > 1e-4) return float(t0);
    if (t1 > 1e-4) return float(t1);
    return std::nullopt;
}

int Dominant(vec3 c) {
    if (c.x > 0.5f && c.y < 0.2f && c.z > 0.5f) return 3;  // magenta
    if (c.y > 0.5f && c.x < 0.2f && c.z < 0.2f) return 1;  // green
    if (c.x > 0.5f && c.y < 0.2f && c.z < 0.2f) return 0;  // red
    if (c.z > 0.5f && c.x < 0.2f && c.y < 0.2f) return 2;  // blue
    return -1;
}

TEST(VerificationScenes, ReflectiveSphereShowsObjectsAtTheirMirroredPositions) {
    const LoadedScene loaded = LoadAsset("reflective_sphere.json");
    const RenderScene& scene = loaded.scene;
    const uint32_t w = 320, h = 240;
    const Image image = RenderCpu(scene, w, h);
    const CameraFrame frame = MakeCameraFrame(scene.camera, w, h);
    // Spheres as the file places them: the unit mirror at the origin, green and magenta.
    struct Ball {
        vec3 c;
        float r;
        int colour;
    };
    const Ball balls[] = {{vec3(2.6f, 0.4f, 2.0f), 0.8f, 1}, {vec3(-1.5f, -1.8f, 3.0f), 0.6f, 3}};
    uint32_t mirrorPixels = 0, agree = 0, greenInMirror = 0, greenRightHalf = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const Ray ray = PrimaryRay(frame, x, y, w, h);
            const auto tMirror = HitSphere(ray.origin, ray.dir, vec3(0), 1.0f);
            bool occluded = false;
            for (const Ball& b : balls)
                if (auto t = HitSphere(ray.origin, ray.dir, b.c, b.r);
                    t && (!tMirror || *t < *tMirror))
                    occluded = true;
            if (!tMirror || occluded) continue;
            ++mirrorPixels;
            const vec3 p = ray.origin + *tMirror * ray.dir;
            const vec3 n = glm::normalize(p);
            const vec3 r = ray.dir - 2.0f * glm::dot(ray.dir, n) * n;
            int expected = -1;
            float nearest = kInfinity;
            for (const Ball& b : balls)
                if (auto t = HitSphere(p, r, b.c, b.r); t && *t < nearest) {
                    nearest = *t;
                    expected = b.colour;
                }
            agree += Dominant(image.At(x, y)) == expected;
            if (expected == 1) {
                ++greenInMirror;
                greenRightHalf += x > w / 2;
            }
        }
    ASSERT_GT(mirrorPixels, 3000u);
    EXPECT_GE(double(agree), 0.995 * mirrorPixels) << agree << " of " << mirrorPixels;
    // The green ball is to the right of and in front of the mirror: its image is on the right.
    EXPECT_GT(greenInMirror, 20u);
    EXPECT_EQ(greenRightHalf, greenInMirror);
}

TEST(VerificationScenes, RefractiveSphereShowsWhatIsBehindItUpsideDown) {
    const LoadedScene loaded = LoadAsset("refractive_sphere.json");
    const uint32_t w = 320, h = 240;
    const Image image = RenderCpu(loaded.scene, w, h);
    const CameraFrame frame = MakeCameraFrame(loaded.scene.camera, w, h);
    // Pixel rows of points on the sphere's vertical axis, seen from the camera.
    auto rowOf = [&](float worldY) {
        const vec3 d = glm::normalize(vec3(0, worldY, 1.0f) - frame.origin);
        const float sy = glm::dot(d, frame.up) / glm::dot(d, frame.forward) / frame.tanHalfFovY;
        return uint32_t((1.0f - sy) * 0.5f * h);
    };
    const uint32_t cx = w / 2;
    int upperInside = 0, lowerInside = 0;
    for (float y = 0.2f; y <= 0.6f; y += 0.1f) {
        upperInside += Dominant(image.At(cx, rowOf(y))) == 2;   // blue: from below the horizon
        lowerInside += Dominant(image.At(cx, rowOf(-y))) == 0;  // red: from above
    }
    EXPECT_EQ(upperInside, 5) << "the upper half of the ball should show the blue lower wall";
    EXPECT_EQ(lowerInside, 5) << "the lower half of the ball should show the red upper wall";
    // Outside the ball the walls appear the right way up.
    EXPECT_EQ(Dominant(image.At(cx, 5)), 0);
    EXPECT_EQ(Dominant(image.At(cx, h - 5)), 2);
}

TEST(VerificationScenes, TeapotShadowFallsWhereTheGeometrySays) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    const LoadedScene loaded = LoadAsset("teapot_shadow.json");
    const RenderScene& scene = loaded.scene;
    const uint32_t w = 240, h = 180;
    const Image image = RenderCpu(scene, w, h);
    const CameraFrame frame = MakeCameraFrame(scene.camera, w, h);
    // The teapot's triangles in world space, tested one by one (no BVH).
    const Instance& pot = scene.instances[1];
    const Blas& blas = *scene.blases[pot.blasId];
    std::vector<Triangle> world;
    for (const Triangle& t : blas.triangles)
        world.push_back({pot.ObjectToWorld().Point(t.v0), pot.ObjectToWorld().Point(t.v1),
                         pot.ObjectToWorld().Point(t.v2)});
    auto hitsTeapot = [&](vec3 o, vec3 d, float tMax) {
        const RaySetup r = MakeRaySetup(Ray{o, tMax, d, 0});
        for (const Triangle& t : world) {
            TriangleHit hit;
            if (IntersectTriangle(t, r, tMax, &hit)) return true;
        }
        return false;
    };
    const vec3 toLight = scene.lights[0].vector;
    uint32_t floorPixels = 0, agree = 0, shadowed = 0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const Ray ray = PrimaryRay(frame, x, y, w, h);
            if (ray.dir.y >= 0) continue;
            const float tFloor = -ray.origin.y / ray.dir.y;
            const vec3 p = ray.origin + tFloor * ray.dir;
            if (std::abs(p.x) > 14 || std::abs(p.z) > 14 || hitsTeapot(ray.origin, ray.dir, tFloor))
                continue;
            ++floorPixels;
            const bool inShadow = hitsTeapot(p + vec3(0, 1e-3f, 0), toLight, kInfinity);
            shadowed += inShadow;
            // Floor: ambient 0.1 alone in shadow, 0.1 + 0.8 n.l when lit.
            const bool renderedDark = image.At(x, y).x < 0.1f + 0.4f * toLight.y;
            agree += renderedDark == inShadow;
        }
    ASSERT_GT(floorPixels, 10000u);
    EXPECT_GT(shadowed, 500u);
    EXPECT_GE(double(agree), 0.995 * floorPixels) << agree << " of " << floorPixels;
}

TEST(VerificationScenes, FullDragonIsRedAndSolid) {
    RTRT_REQUIRE_MODEL(dragon, "dragon_vrip.ply.gz");
    const LoadedScene loaded = LoadAsset("dragon.json");
    EXPECT_EQ(loaded.scene.TriangleCount(), 871414u);
    const uint32_t w = 320, h = 180;
    const Image shaded = RenderCpu(loaded.scene, w, h);
    const Image depth = RenderCpu(loaded.scene, w, h, ViewMode::kDepth);
    uint32_t hits = 0, red = 0;
    for (size_t i = 0; i < shaded.pixels.size(); ++i) {
        if (!std::isfinite(depth.pixels[i].x)) {
            EXPECT_EQ(shaded.pixels[i], loaded.scene.background);
            continue;
        }
        ++hits;
        const vec3 c = shaded.pixels[i];
        red += c.x > 1.5f * c.y && c.x > 1.5f * c.z;
        // The dragon spans z in [-2.5, 2.5] around the origin, 10 units from the camera.
        EXPECT_GT(depth.pixels[i].x, 7.0f);
        EXPECT_LT(depth.pixels[i].x, 13.0f);
    }
    EXPECT_GT(hits, w * h / 20);
    EXPECT_LT(hits, w * h / 2);
    EXPECT_GE(red, hits * 99 / 100);
}

}  // namespace
}  // namespace rtrt
