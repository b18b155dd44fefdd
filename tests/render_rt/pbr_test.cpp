// glTF's metallic-roughness BRDF and its inputs at known answers: GGX, Smith and Schlick against
// their formulas, a white furnace (the BRDF's directional albedo never exceeds 1, and a white
// object in uniform light is no brighter than the light), a normal map that turns the shading as
// the map says, a KHR_texture_transform that moves a texel exactly, and light falloff and spot
// cones at known distances and angles.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <memory>

#include "engine/geometry/mesh_tangents.h"
#include "engine/render_rt/renderer.h"
#include "engine/render_rt/shading/light.h"
#include "engine/render_rt/shading/pbr_brdf.h"
#include "engine/render_rt/shading/texture.h"

namespace rtrt {
namespace {

PbrSample White(float metallic, float roughness) {
    return {vec3(1.0f), metallic, GgxAlpha(roughness), vec3(0.04f), 1.0f, 0.0f};
}

TEST(PbrBrdf, GgxDistributionAtKnownAngles) {
    EXPECT_FLOAT_EQ(GgxDistribution(1.0f, 0.5f), 1.0f / (kPi * 0.25f));
    // alpha = 1 is uniform over the hemisphere of normals: 1 / pi at every angle.
    EXPECT_FLOAT_EQ(GgxDistribution(0.3f, 1.0f), 1.0f / kPi);
    // alpha 0.5 at 30 degrees: a^2 / (pi ((a^2 - 1) cos^2 + 1)^2) = 0.25 / (pi 0.4375^2).
    EXPECT_NEAR(GgxDistribution(std::sqrt(3.0f) / 2.0f, 0.5f), 0.25 / (M_PI * 0.4375 * 0.4375),
                1e-6);
}

TEST(PbrBrdf, SmithVisibilityAtKnownAngles) {
    // alpha 1: V = 0.5 / (n.l + n.v).
    EXPECT_FLOAT_EQ(SmithGgxVisibility(1.0f, 1.0f, 1.0f), 0.25f);
    EXPECT_FLOAT_EQ(SmithGgxVisibility(0.5f, 0.8f, 1.0f), 0.5f / 1.3f);
    // A smooth surface does not mask: V = 1 / (4 n.l n.v).
    EXPECT_NEAR(SmithGgxVisibility(0.5f, 0.8f, 1e-4f), 1.0f / (4.0f * 0.5f * 0.8f), 1e-5f);
    // alpha 0.5, n.l = 0.5, n.v = 0.8, by the formula in double.
    const double a2 = 0.25, l = 0.5, v = 0.8;
    const double expected =
        0.5 / (l * std::sqrt(v * v * (1 - a2) + a2) + v * std::sqrt(l * l * (1 - a2) + a2));
    EXPECT_NEAR(SmithGgxVisibility(0.5f, 0.8f, 0.5f), expected, 1e-6);
}

TEST(PbrBrdf, SchlickFresnelAtKnownAngles) {
    EXPECT_FLOAT_EQ(SchlickFresnel(vec3(0.04f), 1.0f).x, 0.04f);
    EXPECT_FLOAT_EQ(SchlickFresnel(vec3(0.04f), 0.0f).x, 1.0f);
    EXPECT_FLOAT_EQ(SchlickFresnel(vec3(0.04f), 0.5f).x, 0.04f + 0.96f / 32.0f);
}

TEST(PbrBrdf, LambertianLimitIsBaseColourOverPi) {
    // No specular layer (KHR_materials_specular's factor 0): f = baseColour / pi everywhere.
    PbrSample p = White(0.0f, 0.7f);
    p.baseColor = vec3(0.5f, 0.25f, 1.0f);
    p.specularWeight = 0.0f;
    const vec3 f = GltfBrdf(p, vec3(0, 0, 1), glm::normalize(vec3(0.3f, 0.1f, 1)),
                            glm::normalize(vec3(-0.5f, 0.2f, 1)));
    EXPECT_FLOAT_EQ(f.x, 0.5f / kPi);
    EXPECT_FLOAT_EQ(f.y, 0.25f / kPi);
    EXPECT_FLOAT_EQ(f.z, 1.0f / kPi);
}

// The integral of f cos over the hemisphere of light directions for view angle thetaV, by the
// midpoint rule in (cos theta, phi), fine enough for the narrowest lobe below.
double DirectionalAlbedo(const PbrSample& p, float thetaV) {
    const vec3 n(0, 0, 1), v(std::sin(thetaV), 0.0f, std::cos(thetaV));
    const int nMu = 1500, nPhi = 600;
    double sum = 0.0;
    for (int i = 0; i < nMu; ++i) {
        const double mu = (i + 0.5) / nMu;
        const double sinT = std::sqrt(1.0 - mu * mu);
        for (int j = 0; j < nPhi; ++j) {
            const double phi = 2.0 * M_PI * (j + 0.5) / nPhi;
            const vec3 l(float(sinT * std::cos(phi)), float(sinT * std::sin(phi)), float(mu));
            sum += double(GltfBrdf(p, n, v, l).x) * mu;
        }
    }
    return sum * (1.0 / nMu) * (2.0 * M_PI / nPhi);
}

TEST(PbrBrdf, WhiteFurnaceNeverGainsEnergy) {
    for (float metallic : {0.0f, 1.0f})
        for (float roughness : {0.3f, 0.6f, 1.0f})
            for (float thetaV : {0.0f, 0.8f, 1.3f}) {
                const double albedo = DirectionalAlbedo(White(metallic, roughness), thetaV);
                EXPECT_LE(albedo, 1.0 + 2e-3)
                    << "metallic " << metallic << " roughness " << roughness << " view " << thetaV;
                // Single scattering loses energy to masking: at alpha 1 and normal incidence a
                // white metal keeps 1 - ln 2 = 0.307 (the integral in closed form).
                EXPECT_GT(albedo, metallic == 1.0f && roughness == 1.0f ? 0.3 : 0.5)
                    << "metallic " << metallic << " roughness " << roughness << " view " << thetaV;
            }
    EXPECT_NEAR(DirectionalAlbedo(White(1.0f, 1.0f), 0.0f), 1.0 - std::log(2.0), 1e-3);
}

// How a normal map finds its tangents: per face from the uvs at the hit, or stored per vertex.
enum class Tangents { kPerFace, kGenerated };

// A quad filling [-1, 1]^2 in z = 0 (uv (0, 0) at its top-left corner, glTF's convention), seen
// by a 90-degree camera from z = 1 so that it fills the square image.
RenderScene QuadScene(const PbrMaterial& pbr, uint32_t baseColorTexture = kNoTexture,
                      Tangents tangents = Tangents::kPerFace) {
    RenderScene scene;
    TriangleMesh quad;
    quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    quad.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    quad.indices = {{0, 1, 2}, {0, 2, 3}};
    if (tangents == Tangents::kGenerated) GenerateTangents(quad);
    scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(quad)));
    Material approximation;
    approximation.baseColorTexture = baseColorTexture;
    scene.AddPbrMaterial(approximation, pbr);
    scene.AddInstance(0, 0, glm::mat4(1.0f));
    scene.camera.position = vec3(0, 0, 1);
    scene.camera.fovYDegrees = 90.0f;
    scene.background = vec3(0.0f);
    scene.BuildTlas();
    return scene;
}

Image Render(const RenderScene& scene, uint32_t size, uint32_t maxDepth = 1) {
    RenderSettings s;
    s.width = s.height = size;
    s.maxDepth = maxDepth;
    return RenderRaw(scene, s);
}

// A Lambertian PBR material (no specular layer, no ambient light).
PbrMaterial Lambert() {
    PbrMaterial p;
    p.metallic = 0.0f;
    p.roughness = 1.0f;
    p.specularWeight = 0.0f;
    p.ambientLight = vec3(0.0f);
    return p;
}

TEST(PbrShading, NormalMappedQuadFollowsTheMap) {
    // One texel tilting the normal by 30 degrees towards +x of the map (the direction of
    // increasing u), another towards +y (decreasing v, the image's up).
    auto texel = [](vec3 m) {
        auto byte = [](float c) { return uint32_t(std::lround((c * 0.5f + 0.5f) * 255.0f)); };
        return byte(m.x) | (byte(m.y) << 8) | (byte(m.z) << 16) | 0xff000000u;
    };
    auto decoded = [](uint32_t t) {
        auto c = [&](int k) { return float((t >> (8 * k)) & 0xffu) / 255.0f * 2.0f - 1.0f; };
        return glm::normalize(vec3(c(0), c(1), c(2)));
    };
    const float s = 0.5f, c = std::sqrt(3.0f) / 2.0f;
    for (const Tangents tangents : {Tangents::kPerFace, Tangents::kGenerated})
        for (const vec3 tilt : {vec3(s, 0, c), vec3(0, s, c)}) {
            PbrMaterial pbr = Lambert();
            RenderScene scene = QuadScene(pbr, kNoTexture, tangents);
            ASSERT_EQ(scene.blases[0]->tangents.empty(), tangents == Tangents::kPerFace);
            Texture map;
            map.width = map.height = 1;
            map.filter = TextureFilter::kNearest;
            const uint32_t rgba = texel(tilt);
            scene.pbrMaterials[0].normalTexture = scene.AddTexture(map, &rgba);
            // On the quad, +x of the map is world +x and +y of the map world +y.
            const vec3 expectedNormal = decoded(rgba);
            for (const vec3 toLight :
                 {vec3(0, 0, 1), glm::normalize(vec3(1, 0, 1)), glm::normalize(vec3(0, 1, 2)),
                  glm::normalize(vec3(-1, 0, 3))}) {
                scene.lights = {Light{toLight, LightType::kDirectional, vec3(1.0f)}};
                const Image image = Render(scene, 8);
                // A light's colour is what a white Lambertian surface facing it shows (light.h).
                const float expected = std::max(0.0f, glm::dot(expectedNormal, toLight));
                for (uint32_t y = 0; y < 8; y += 3)
                    for (uint32_t x = 0; x < 8; x += 3)
                        EXPECT_NEAR(image.At(x, y).x, expected, 2e-6f)
                            << "tilt " << tilt.x << "," << tilt.y << " light " << toLight.x << ","
                            << toLight.y << " pixel " << x << "," << y;
            }
        }
}

TEST(PbrShading, MirroredUvsKeepTheMapsUpTheImagesUp) {
    // The same +y tilt on a quad whose v runs the other way: the bitangent follows decreasing v.
    for (const Tangents tangents : {Tangents::kPerFace, Tangents::kGenerated}) {
        PbrMaterial pbr = Lambert();
        RenderScene scene;
        TriangleMesh quad;
        quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
        quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};  // v up the quad
        quad.indices = {{0, 1, 2}, {0, 2, 3}};
        if (tangents == Tangents::kGenerated) {
            GenerateTangents(quad);
            EXPECT_EQ(quad.tangents[0], vec4(1, 0, 0, -1));  // the bitangent n x t = +y is +v
        }
        scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(quad)));
        scene.AddPbrMaterial(Material{}, pbr);
        scene.AddInstance(0, 0, glm::mat4(1.0f));
        scene.camera.position = vec3(0, 0, 1);
        scene.camera.fovYDegrees = 90.0f;
        scene.BuildTlas();
        Texture map;
        map.width = map.height = 1;
        const uint32_t up = 128u | (238u << 8) | (238u << 16);  // +y tilt, about 45 degrees
        scene.pbrMaterials[0].normalTexture = scene.AddTexture(map, &up);
        scene.lights = {Light{vec3(0, -1, 0.01f), LightType::kDirectional, vec3(1.0f)}};
        // The map's +y is now world -y: a light from -y lights the quad.
        EXPECT_GT(Render(scene, 4).At(1, 1).x, 0.2f);
        scene.lights = {
            Light{glm::normalize(vec3(0, 1, 0.01f)), LightType::kDirectional, vec3(1.0f)}};
        EXPECT_EQ(Render(scene, 4).At(1, 1).x, 0.0f);
    }
}

// Two triangles sharing an edge whose uvs mirror each other: the shared vertices are split, so
// that each triangle keeps its own frame (opposite handedness) instead of an average.
TEST(MeshTangents, MirroredNeighboursSplitTheirSharedVertices) {
    TriangleMesh mesh;
    mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    mesh.uvs = {{0, 1}, {1, 1}, {1, 0}, {2, 1}};
    mesh.indices = {{0, 1, 2}, {0, 2, 3}};
    GenerateTangents(mesh);
    ASSERT_EQ(mesh.positions.size(), 6u);
    ASSERT_EQ(mesh.uvs.size(), 6u);
    ASSERT_EQ(mesh.tangents.size(), 6u);
    EXPECT_EQ(mesh.indices[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(mesh.indices[1], glm::uvec3(4, 5, 3));
    EXPECT_EQ(mesh.positions[4], mesh.positions[0]);
    EXPECT_EQ(mesh.positions[5], mesh.positions[2]);
    for (uint32_t v : {0u, 1u, 2u}) EXPECT_EQ(mesh.tangents[v], vec4(1, 0, 0, 1)) << v;
    // Triangle 1: dp/du = (0, 1, 0) and dp/dv = (-2, -1, 0), so n x t = -x points along +v.
    const vec4 mirrored(0, 1, 0, -1);
    for (uint32_t v : {3u, 4u, 5u}) {
        EXPECT_NEAR(glm::distance(mesh.tangents[v], mirrored), 0.0f, 1e-6f) << v;
    }
}

// Stored tangents are followed, not re-derived from the uvs: a quad whose file says its tangent
// is +y (uvs as the other quads) turns the map's +x tilt towards world +y; mirrored by its
// instance (x -> -x), the bitangent turns with it.
TEST(PbrShading, StoredTangentsOrientTheMap) {
    TriangleMesh quad;
    quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    quad.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    quad.indices = {{0, 1, 2}, {0, 2, 3}};
    quad.tangents.assign(4, vec4(0, 1, 0, 1));                 // bitangent n x t = -x
    const uint32_t tiltX = 238u | (128u << 8) | (238u << 16);  // map +x, about 45 degrees
    const uint32_t tiltY = 128u | (238u << 8) | (238u << 16);  // map +y
    struct Case {
        uint32_t texel;
        float mirror;  // the instance's x scale
        vec3 lit;      // a light from here lights the quad; from its mirror image it does not
    };
    for (const Case& c :
         {Case{tiltX, 1.0f, vec3(0, 1, 0.01f)}, Case{tiltY, 1.0f, vec3(-1, 0, 0.01f)},
          Case{tiltY, -1.0f, vec3(1, 0, 0.01f)}}) {
        RenderScene scene;
        scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(quad)));
        scene.AddPbrMaterial(Material{}, Lambert());
        // A mirrored instance's front face points -z; the camera looks at whichever face it sees.
        scene.AddInstance(0, 0, glm::scale(glm::mat4(1.0f), vec3(c.mirror, 1, 1)));
        scene.camera.position = vec3(0, 0, 1);
        scene.camera.fovYDegrees = 90.0f;
        scene.BuildTlas();
        Texture map;
        map.width = map.height = 1;
        scene.pbrMaterials[0].normalTexture = scene.AddTexture(map, &c.texel);
        scene.lights = {Light{glm::normalize(c.lit), LightType::kDirectional, vec3(1.0f)}};
        EXPECT_GT(Render(scene, 4).At(1, 1).x, 0.2f) << c.texel << " " << c.mirror;
        scene.lights = {Light{glm::normalize(vec3(-c.lit.x, -c.lit.y, c.lit.z)),
                              LightType::kDirectional, vec3(1.0f)}};
        EXPECT_EQ(Render(scene, 4).At(1, 1).x, 0.0f) << c.texel << " " << c.mirror;
    }
}

TEST(PbrShading, WhiteObjectsInUniformLightAreNoBrighterThanIt) {
    // No lights: ambient light 1 all round, and a background of 1 that mirror rays see.
    for (float metallic : {0.0f, 1.0f})
        for (float roughness : {0.0f, 0.2f, 0.5f, 1.0f}) {
            PbrMaterial pbr;
            pbr.metallic = metallic;
            pbr.roughness = roughness;
            pbr.ambientLight = vec3(1.0f);
            RenderScene scene = QuadScene(pbr);
            scene.background = vec3(1.0f);
            const Image image = Render(scene, 8, 2);
            for (uint32_t y = 0; y < 8; ++y)
                for (uint32_t x = 0; x < 8; ++x) {
                    EXPECT_LE(image.At(x, y).x, 1.0f + 1e-6f)
                        << "metallic " << metallic << " roughness " << roughness;
                    EXPECT_GT(image.At(x, y).x, 0.9f)
                        << "metallic " << metallic << " roughness " << roughness;
                }
        }
}

TEST(PbrShading, EmissionAddsItsTexelsAndOcclusionDarkensOnlyAmbientLight) {
    PbrMaterial pbr = Lambert();
    pbr.baseColor = vec3(0.0f);
    pbr.emissive = vec3(2.0f);
    RenderScene scene = QuadScene(pbr);
    Texture t;
    t.width = t.height = 1;
    const uint32_t quarter = 64u | (64u << 8) | (64u << 16);
    scene.pbrMaterials[0].emissiveTexture = scene.AddTexture(t, &quarter);
    EXPECT_FLOAT_EQ(Render(scene, 2).At(0, 0).x, 2.0f * 64.0f / 255.0f);
    // Occlusion of strength 0.5 at texel 0 halves ambient light and leaves direct light alone.
    scene.pbrMaterials[0] = Lambert();
    scene.pbrMaterials[0].ambientLight = vec3(0.2f);
    scene.pbrMaterials[0].occlusionStrength = 0.5f;
    const uint32_t black = 0;
    scene.pbrMaterials[0].occlusionTexture = scene.AddTexture(t, &black);
    scene.lights = {Light{vec3(0, 0, 1), LightType::kDirectional, vec3(1.0f)}};
    EXPECT_NEAR(Render(scene, 2).At(0, 0).x, 0.5f * 0.2f + 1.0f, 1e-6f);
}

TEST(TextureTransform, OffsetAndRotationMoveATexelExactly) {
    // 4 x 4 texels numbered 0..15, nearest: texel (x, y) holds 10 (y * 4 + x).
    uint32_t texels[16];
    for (uint32_t i = 0; i < 16; ++i) texels[i] = 10u * i;
    Texture t;
    t.width = t.height = 4;
    t.filter = TextureFilter::kNearest;
    auto texelAt = [&](vec2 uv) {
        return int(std::lround(SampleTexture(t, texels, uv).x * 25.5f));
    };
    EXPECT_EQ(texelAt({0.125f, 0.125f}), 0);
    SetUvTransform(&t, vec2(0.25f, 0.5f), 0.0f, vec2(1.0f));
    EXPECT_EQ(texelAt({0.125f, 0.125f}), 2 * 4 + 1);  // one texel right, two down
    SetUvTransform(&t, vec2(0.0f), 0.0f, vec2(2.0f, 1.0f));
    EXPECT_EQ(texelAt({0.3f, 0.125f}), 2);  // u 0.6
    // A quarter turn: (u, v) -> (v, -u), so (0.125, 0.375) samples (0.375, 0.875).
    SetUvTransform(&t, vec2(0.0f), float(M_PI / 2), vec2(1.0f));
    EXPECT_EQ(texelAt({0.125f, 0.375f}), 3 * 4 + 1);
}

TEST(LightFalloff, InverseSquareWithRangeAndSpotCone) {
    Light point;
    point.type = LightType::kPoint;
    point.falloff = 1;
    EXPECT_FLOAT_EQ(LightAttenuation(point, vec3(0, 0, 2), vec3(0, 0, 1)), 0.25f);
    EXPECT_FLOAT_EQ(LightAttenuation(point, vec3(3, 4, 0), vec3(0.6f, 0.8f, 0)), 1.0f / 25.0f);
    // Range 4 at distance 2: (1 - (2/4)^4)^2 / 4; nothing at or beyond the range.
    point.range = 4.0f;
    EXPECT_FLOAT_EQ(LightAttenuation(point, vec3(0, 0, 2), vec3(0, 0, 1)),
                    (1.0f - 1.0f / 16.0f) * (1.0f - 1.0f / 16.0f) / 4.0f);
    EXPECT_EQ(LightAttenuation(point, vec3(0, 0, 4), vec3(0, 0, 1)), 0.0f);
    EXPECT_EQ(LightAttenuation(point, vec3(0, 0, 9), vec3(0, 0, 1)), 0.0f);
    // rtrt's own lights without falloff stay as they were.
    Light plain;
    plain.type = LightType::kPoint;
    EXPECT_FALSE(LightAttenuates(plain));
    // A spot shining down -z with cone 20 to 40 degrees: full inside, none outside, and the
    // specification's smooth weight between.
    Light spot;
    spot.type = LightType::kSpot;
    spot.spotAxis = vec3(0, 0, -1);
    SetSpotCone(&spot, 20.0f * kPi / 180.0f, 40.0f * kPi / 180.0f);
    auto at = [&](float degrees) {
        const float a = degrees * kPi / 180.0f;
        const vec3 l(std::sin(a), 0.0f, std::cos(a));  // from the point up to the light
        return LightAttenuation(spot, l, l);
    };
    EXPECT_FLOAT_EQ(at(0.0f), 1.0f);
    EXPECT_FLOAT_EQ(at(15.0f), 1.0f);
    EXPECT_EQ(at(45.0f), 0.0f);
    const double c20 = std::cos(20 * M_PI / 180), c40 = std::cos(40 * M_PI / 180);
    const double w = (std::cos(30 * M_PI / 180) - c40) / (c20 - c40);
    EXPECT_NEAR(at(30.0f), w * w, 1e-5);
}

TEST(LightFalloff, PointLightOverAPlaneFallsOffWithDistance) {
    // A Lambertian quad under a point light of 4 at heights 1 and 2 on its axis: a pixel sees
    // 4 cos / d^2.
    for (float h : {1.0f, 2.0f}) {
        RenderScene scene = QuadScene(Lambert());
        scene.camera.position = vec3(0, 0, 0.5f);
        Light light;
        light.type = LightType::kPoint;
        light.vector = vec3(0, 0, h);
        light.color = vec3(4.0f);
        light.falloff = 1;
        scene.lights = {light};
        const Image image = Render(scene, 2);
        // Pixel centres look 0.25 off the axis at z = 0.5: the point is (±0.25, ±0.25, 0).
        const vec3 p(0.25f, 0.25f, 0.0f), toLight = light.vector - p;
        const float expected = 4.0f / glm::dot(toLight, toLight) * glm::normalize(toLight).z;
        EXPECT_NEAR(image.At(1, 0).x, expected, 1e-5f * expected) << h;
    }
}

// A point light exactly at the shaded point has no direction: it lights nothing there, where
// normalising the zero vector had made the pixel NaN (black in an 8-bit file).
TEST(LightFalloff, APointLightAtTheShadedPointAddsNothing) {
    for (uint32_t falloff : {0u, 1u}) {
        RenderScene scene = QuadScene(Lambert());
        scene.camera.position = vec3(0, 0, 0.5f);  // the one pixel's ray meets the quad at 0
        Light light;
        light.type = LightType::kPoint;
        light.vector = vec3(0.0f);
        light.falloff = falloff;
        scene.lights = {light};
        const Image image = Render(scene, 1);
        EXPECT_EQ(image.At(0, 0), vec3(0.0f)) << falloff;
    }
}

TEST(PbrFeatures, KernelsFollowTheMaterialsInstancesUse) {
    // A rough PBR material: no mirror rays; with a metallic-roughness texture that may make
    // parts of it smooth, mirror rays.
    PbrMaterial rough;
    rough.roughness = 1.0f;
    RenderScene scene = QuadScene(rough);
    EXPECT_EQ(scene.Features() & kFeatureReflection, 0u);
    EXPECT_NE(scene.Features() & kFeaturePbr, 0u);
    Texture t;
    t.width = t.height = 1;
    const uint32_t texel = 0;
    scene.pbrMaterials[0].metallicRoughnessTexture = scene.AddTexture(t, &texel);
    EXPECT_NE(scene.Features() & kFeatureReflection, 0u);
    // A glass material no instance uses (a spawn palette's) adds no refraction.
    Material glass;
    glass.transmissivity = 1.0f;
    scene.AddMaterial(glass);
    EXPECT_EQ(scene.Features() & kFeatureRefraction, 0u);
    scene.AddInstance(0, 1, glm::translate(glm::mat4(1.0f), vec3(0, 0, -3)));
    EXPECT_NE(scene.Features() & kFeatureRefraction, 0u);
}

}  // namespace
}  // namespace rtrt
