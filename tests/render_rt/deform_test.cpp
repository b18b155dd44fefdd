// Deforming meshes on the CPU back end (render_rt alone): the vertex formulas against their
// closed forms (wave, twist, skinning, morphing), the refit tree after many deforming frames
// (every box bounds what it holds; traversal equals brute force on 100,000 rays), rebuilt trees,
// the rebuild policy's decisions (when and how deterministically), and the frame renderer's
// images of a deformed mesh against a static BLAS built from the same triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <random>

#include "engine/render_rt/cpu/cpu_deformer.h"
#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"
#include "tests/bvh/tree_checks.h"

namespace rtrt {
namespace {

using test::ExpectMatchesBruteForce;
using test::ExpectWellFormed;

// A UV sphere of radius 1 at the origin, with its normals: 2 x rings x segments triangles.
TriangleMesh UvSphere(uint32_t rings, uint32_t segments) {
    TriangleMesh mesh;
    for (uint32_t r = 0; r <= rings; ++r)
        for (uint32_t s = 0; s <= segments; ++s) {
            const float theta = kPi * float(r) / float(rings);
            const float phi = 2.0f * kPi * float(s) / float(segments);
            const vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta),
                         std::sin(theta) * std::sin(phi));
            mesh.positions.push_back(p);
            mesh.normals.push_back(p);
        }
    for (uint32_t r = 0; r < rings; ++r)
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t a = r * (segments + 1) + s, b = a + segments + 1;
            mesh.indices.push_back({a, b, a + 1});
            mesh.indices.push_back({a + 1, b, b + 1});
        }
    return mesh;
}

// A scene of one deforming sphere (and its rest BLAS).
struct DeformingScene {
    RenderScene scene;
    uint32_t deformation = 0;

    explicit DeformingScene(ProceduralDeform procedural, uint32_t rings = 24,
                            BvhBuildOptions options = {}, bool colored = false) {
        auto mesh = std::make_shared<DeformableMesh>();
        mesh->rest = UvSphere(rings, 2 * rings);
        if (colored)
            for (vec3 p : mesh->rest.positions) mesh->rest.colors.push_back(0.5f * p + 0.5f);
        const uint32_t rest =
            scene.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(mesh->rest, options)));
        const uint32_t meshId = scene.AddDeformableMesh(mesh);
        deformation = scene.AddDeformation(meshId, rest);
        scene.deformations[deformation].procedural = procedural;
        scene.AddMaterial(Material{});
        scene.AddInstance(scene.deformations[deformation].blasId, 0, glm::mat4(1.0f));
        scene.lights.push_back(
            Light{glm::normalize(vec3(1, 2, 3)), LightType::kDirectional, vec3(1)});
        scene.camera.position = vec3(0, 0.5f, 4);
        scene.camera.forward = vec3(0, -0.1f, -1);
        scene.BuildTlas();  // over the rest pose, for one-shot images
    }
    void At(float t) { scene.deformations[deformation].procedural.time = t; }
};

ProceduralDeform Twist(float angle) {
    ProceduralDeform d;
    d.kind = ProceduralDeformKind::kTwist;
    d.axis = 1;
    d.amplitude = angle;
    d.speed = 1.0f;
    return d;
}

ProceduralDeform Wave(float amplitude) {
    ProceduralDeform d;
    d.kind = ProceduralDeformKind::kWave;
    d.axis = 1;
    d.along = 0;
    d.amplitude = amplitude;
    d.wavelength = 0.8f;
    d.speed = 0.5f;
    return d;
}

DeformMeshView ViewOf(const DeformableMesh& mesh) { return HostMeshView(mesh); }

// A deformation's slot keeps no parts in its outline (its box follows the deformation, the parts
// would not), while the rest BLAS it started from keeps them.
TEST(DeformingScene, SlotsThatDeformKeepNoOutlineParts) {
    DeformingScene d(ProceduralDeform{});
    const std::vector<BlasOutline> outlines = d.scene.BlasOutlines();
    const uint32_t slot = d.scene.deformations[d.deformation].blasId;
    ASSERT_EQ(outlines.size(), d.scene.blases.size());
    EXPECT_EQ(outlines[slot].partCount, 0u);
    EXPECT_EQ(outlines[0].partCount, BlasOutline::kMaxParts);
    EXPECT_EQ(d.scene.BlasOutlines(slot).size(), d.scene.blases.size() - slot);
}

TEST(DeformVertex, WaveMovesEachVertexByTheFormula) {
    DeformableMesh mesh;
    mesh.rest = UvSphere(8, 16);
    const DeformMeshView view = ViewOf(mesh);
    ProceduralDeform wave = Wave(0.1f);
    wave.time = 0.3f;
    wave.centre = vec3(0.25f, 0.0f, 0.0f);
    const DeformPose pose{wave, nullptr, nullptr};
    for (uint32_t v = 0; v < mesh.VertexCount(); ++v) {
        vec3 n;
        const vec3 got = DeformVertex(view, pose, v, &n);
        const vec3 p = mesh.rest.positions[v];
        const double phase = 2.0 * M_PI * ((double(p.x) - 0.25) - 0.5 * 0.3) / 0.8;
        EXPECT_FLOAT_EQ(got.x, p.x);
        EXPECT_NEAR(got.y, double(p.y) + 0.1 * std::sin(phase), 1e-6);
        EXPECT_FLOAT_EQ(got.z, p.z);
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    }
}

TEST(DeformVertex, TwistTurnsEachVertexAboutTheAxis) {
    DeformableMesh mesh;
    mesh.rest = UvSphere(8, 16);
    const DeformMeshView view = ViewOf(mesh);
    ProceduralDeform twist = Twist(1.2f);
    twist.time = 0.7f;
    const DeformPose pose{twist, nullptr, nullptr};
    for (uint32_t v = 0; v < mesh.VertexCount(); ++v) {
        vec3 n;
        const vec3 got = DeformVertex(view, pose, v, &n);
        const vec3 p = mesh.rest.positions[v];
        const double angle = 1.2 * std::sin(0.7) * p.y;
        // Rodrigues about +y: x' = x cos + z sin, z' = -x sin + z cos.
        EXPECT_NEAR(got.x, p.x * std::cos(angle) + p.z * std::sin(angle), 1e-6);
        EXPECT_FLOAT_EQ(got.y, p.y);
        EXPECT_NEAR(got.z, -p.x * std::sin(angle) + p.z * std::cos(angle), 1e-6);
    }
}

// A twist about a far centre (1e7 away) at angle 0 leaves every vertex exactly where it is (it
// was rebuilt from the centre, rounding at the centre's magnitude: the mesh came apart in slabs).
TEST(DeformVertex, NoTwistAboutAFarCentreIsNoChange) {
    DeformableMesh mesh;
    mesh.rest = UvSphere(8, 16);
    const DeformMeshView view = ViewOf(mesh);
    ProceduralDeform twist = Twist(1.2f);
    twist.time = 0.0f;  // sin(speed * time) = 0
    twist.centre = vec3(0.0f, 1e7f, 0.0f);
    const DeformPose pose{twist, nullptr, nullptr};
    for (uint32_t v = 0; v < mesh.VertexCount(); ++v) {
        vec3 n;
        EXPECT_EQ(DeformVertex(view, pose, v, &n), mesh.rest.positions[v]) << v;
    }
}

// The deformed normal is perpendicular to every deformed tangent (the Jacobian's image of a
// tangent, measured by a central difference), for both formulas at many points.
TEST(DeformVertex, NormalsStayPerpendicularToTheDeformedSurface) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (ProceduralDeform f : {Wave(0.2f), Twist(2.0f)}) {
        f.time = 0.4f;
        for (int k = 0; k < 200; ++k) {
            const vec3 p(u(rng), u(rng), u(rng));
            const vec3 n0 = glm::normalize(vec3(u(rng), u(rng), u(rng)));
            vec3 t0 = glm::cross(n0, vec3(0.3f, 0.5f, 0.8f));
            t0 = glm::normalize(t0);
            const float h = 1e-3f;
            vec3 pa = p + h * t0, pb = p - h * t0, pc = p, n = n0, na = n0, nb = n0;
            ApplyProcedural(f, pa, na);
            ApplyProcedural(f, pb, nb);
            ApplyProcedural(f, pc, n);
            const vec3 tangent = (pa - pb) / (2.0f * h);
            EXPECT_NEAR(glm::dot(glm::normalize(n), glm::normalize(tangent)), 0.0f, 2e-3f)
                << "kind " << uint32_t(f.kind) << " at point " << k;
        }
    }
}

// Linear blend skinning of one vertex between two known joints: the blend of the two matrices
// applied to the rest position, the normal by the blend's inverse transpose.
TEST(DeformVertex, SkinBlendsTheJointMatricesByWeight) {
    DeformableMesh mesh;
    mesh.rest.positions = {vec3(1.0f, 2.0f, 0.0f)};
    mesh.rest.normals = {vec3(1.0f, 0.0f, 0.0f)};
    mesh.influences = 4;
    mesh.jointCount = 2;
    mesh.joints = {0, 1, 0, 0};
    mesh.weights = {0.25f, 0.75f, 0.0f, 0.0f};
    // Joint 0 moves by (0, 0, 3); joint 1 turns 90 degrees about z.
    const Affine j0 = AffineFromMat4(glm::translate(glm::mat4(1.0f), vec3(0, 0, 3)));
    const Affine j1 = AffineFromMat4(glm::rotate(glm::mat4(1.0f), kPi / 2, vec3(0, 0, 1)));
    const Affine joints[2] = {j0, j1};
    const DeformPose pose{ProceduralDeform{}, joints, nullptr};
    vec3 n;
    const vec3 got = DeformVertex(ViewOf(mesh), pose, 0, &n);
    // 0.25 (1, 2, 3) + 0.75 (-2, 1, 0)
    EXPECT_NEAR(got.x, -1.25f, 1e-6f);
    EXPECT_NEAR(got.y, 1.25f, 1e-6f);
    EXPECT_NEAR(got.z, 0.75f, 1e-6f);
    // The blended linear part is [[0.25, -0.75, 0], [0.75, 0.25, 0], [0, 0, 1]], a rotation
    // scaled by sqrt(0.625): the normal turns with it.
    const vec3 expected = glm::normalize(vec3(0.25f, 0.75f, 0.0f));
    EXPECT_NEAR(n.x, expected.x, 1e-6f);
    EXPECT_NEAR(n.y, expected.y, 1e-6f);
    EXPECT_NEAR(n.z, 0.0f, 1e-6f);
}

TEST(DeformVertex, MorphAddsTheWeightedDeltas) {
    DeformableMesh mesh;
    mesh.rest.positions = {vec3(0.0f), vec3(1.0f, 0.0f, 0.0f)};
    mesh.targetCount = 2;
    mesh.positionDeltas = {vec3(0, 1, 0), vec3(0, 2, 0), vec3(0, 0, 4), vec3(8, 0, 0)};
    const float weights[2] = {0.5f, 0.25f};
    const DeformPose pose{ProceduralDeform{}, nullptr, weights};
    vec3 n;
    const vec3 a = DeformVertex(ViewOf(mesh), pose, 0, &n);
    const vec3 b = DeformVertex(ViewOf(mesh), pose, 1, &n);
    EXPECT_EQ(a, vec3(0.0f, 0.5f, 1.0f));
    EXPECT_EQ(b, vec3(3.0f, 1.0f, 0.0f));
}

std::vector<BlasView> Views(const RenderScene& s) {
    std::vector<BlasView> v;
    for (const auto& b : s.blases) v.push_back(b->View());
    return v;
}
std::vector<Aabb> Bounds(const RenderScene& s) {
    std::vector<Aabb> v;
    for (const auto& b : s.blases) v.push_back(b->bounds);
    return v;
}

// The deformation's tree after FRAMES frames STEP apart in time under MODE; each frame deforms
// it, and under kAlwaysRebuild rebuilds it.
Blas TreeAfter(DeformingScene& s, BlasRebuildPolicy::Mode mode, int frames, float step) {
    BlasRebuildPolicy policy;
    policy.mode = mode;
    CpuDeformer deformer(policy);
    std::vector<BlasView> views = Views(s.scene);
    std::vector<Aabb> bounds = Bounds(s.scene);
    const uint32_t d = s.deformation;
    for (int frame = 0; frame < frames; ++frame) {
        s.At(step * float(frame));
        const DeformStats stats = deformer.Update(s.scene, std::span(&d, 1), views, bounds);
        EXPECT_EQ(stats.deformed, 1u);
        EXPECT_EQ(stats.rebuilt, mode == BlasRebuildPolicy::Mode::kAlwaysRebuild ? 1u : 0u);
    }
    return deformer.Snapshot(d);
}

TEST(CpuDeformer, RefitTreeStaysExactAfterManyDeformingFrames) {
    DeformingScene s(Twist(2.5f));
    BlasRebuildPolicy refitOnly;
    refitOnly.mode = BlasRebuildPolicy::Mode::kAlwaysRefit;
    CpuDeformer deformer(refitOnly);
    std::vector<BlasView> views = Views(s.scene);
    std::vector<Aabb> bounds = Bounds(s.scene);
    const uint32_t d = s.deformation;
    for (int frame = 0; frame < 120; ++frame) {
        s.At(0.05f * float(frame));
        const DeformStats stats = deformer.Update(s.scene, std::span(&d, 1), views, bounds);
        ASSERT_EQ(stats.deformed, 1u);
        ASSERT_EQ(stats.rebuilt, 0u);
        if (frame % 30 == 0) ExpectWellFormed(deformer.Snapshot(d));
    }
    const Blas blas = deformer.Snapshot(d);
    ExpectWellFormed(blas);
    ExpectMatchesBruteForce(blas, 11);
    const Aabb root = bounds[s.scene.deformations[d].blasId];
    EXPECT_EQ(root.min, blas.nodes[0].boundsMin);
    EXPECT_EQ(root.max, blas.nodes[0].boundsMax);
    EXPECT_EQ(views[s.scene.deformations[d].blasId].nodes4, nullptr);
    // An unchanged pose is not touched.
    EXPECT_EQ(deformer.Update(s.scene, {}, views, bounds).deformed, 0u);
}

// A spatial-split rest tree (some triangles in several leaves) deforms too: every slot takes its
// triangle's deformed corners and the refit bounds them whole.
TEST(CpuDeformer, SpatialSplitRestTreeRefitsExactly) {
    BvhBuildOptions sbvh;
    sbvh.builder = BvhBuilder::kSpatialSah;
    DeformingScene s(Twist(2.5f), 12, sbvh);  // coarse enough for its triangles to be split
    const Blas& rest = *s.scene.blases[s.scene.deformations[s.deformation].blasId];
    ASSERT_GT(rest.PrimCount(), rest.SourcePrimCount()) << "no triangle was split";
    const Blas blas = TreeAfter(s, BlasRebuildPolicy::Mode::kAlwaysRefit, 30, 0.05f);
    ASSERT_EQ(blas.PrimCount(), rest.PrimCount());
    // Every leaf bounds the whole triangles of its slots, however the rest tree clipped them.
    uint32_t slots = 0;
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
        const BvhNode& node = blas.nodes[stack.back()];
        stack.pop_back();
        if (!node.IsLeaf()) {
            stack.push_back(node.leftFirst);
            stack.push_back(node.leftFirst + 1);
            continue;
        }
        for (uint32_t slot = node.leftFirst; slot < node.leftFirst + node.primCount; ++slot) {
            EXPECT_TRUE(node.Bounds().Contains(blas.triangles[slot].Bounds())) << "slot " << slot;
            ++slots;
        }
    }
    EXPECT_EQ(slots, blas.PrimCount());
    ExpectMatchesBruteForce(blas, 13);
}

TEST(CpuDeformer, RebuiltTreeIsAValidLbvhOfTheDeformedTriangles) {
    DeformingScene s(Wave(0.3f));
    const Blas blas = TreeAfter(s, BlasRebuildPolicy::Mode::kAlwaysRebuild, 3, 0.3f);
    EXPECT_EQ(blas.nodes.size(), 2 * blas.PrimCount());  // one triangle per leaf
    ExpectWellFormed(blas);
    ExpectMatchesBruteForce(blas, 12);
}

// Vertex colours follow their triangles into each rebuilt tree's leaf order, and back out of it
// into a rest mesh.
TEST(CpuDeformer, VertexColoursFollowTheirTrianglesThroughRebuilds) {
    DeformingScene s(Twist(2.0f), 12, {}, true);
    const Blas blas = TreeAfter(s, BlasRebuildPolicy::Mode::kAlwaysRebuild, 3, 0.5f);
    const TriangleMesh& rest = s.scene.deformableMeshes[0]->rest;
    const Blas& restTree = *s.scene.blases[0];
    ASSERT_EQ(blas.colors.size(), blas.PrimCount());
    ASSERT_EQ(restTree.colors.size(), restTree.PrimCount());
    uint32_t moved = 0;
    for (uint32_t slot = 0; slot < blas.PrimCount(); ++slot) {
        const glm::uvec3 idx = rest.indices[blas.primIds[slot]];
        const TriangleColors want =
            TriangleColors::Pack(rest.colors[idx.x], rest.colors[idx.y], rest.colors[idx.z]);
        for (int k = 0; k < 9; ++k) EXPECT_EQ(blas.colors[slot].rgb[k], want.rgb[k]) << slot;
        moved += blas.primIds[slot] != restTree.primIds[slot];
    }
    EXPECT_GT(moved, 0u) << "the rebuilt tree should order the triangles otherwise";
    const TriangleMesh back = RestMeshOfBlas(blas).rest;
    ASSERT_EQ(back.colors.size(), 3 * size_t(blas.PrimCount()));
    for (uint32_t slot = 0; slot < blas.PrimCount(); ++slot)
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(back.colors[3 * slot + k], blas.colors[slot].Corner(k));
}

// The policy rebuilds in the frame after a refit let the cost pass (1 + growth) x the cost of the
// last build, and only then; two runs decide alike.
TEST(CpuDeformer, RebuildsWhenTheCostDriftsAndDecidesAlikeRunToRun) {
    auto run = [] {
        DeformingScene s(Twist(4.0f));
        CpuDeformer deformer;
        std::vector<BlasView> views = Views(s.scene);
        std::vector<Aabb> bounds = Bounds(s.scene);
        const uint32_t d = s.deformation;
        const float growth = deformer.Plan().Policy().maxSahGrowth;
        std::vector<int> rebuilds;
        bool due = false;
        for (int frame = 0; frame < 80; ++frame) {
            s.At(0.04f * float(frame));
            const DeformStats stats = deformer.Update(s.scene, std::span(&d, 1), views, bounds);
            EXPECT_EQ(stats.rebuilt == 1, due) << "frame " << frame;
            if (stats.rebuilt) rebuilds.push_back(frame);
            due = deformer.Plan().LastCost(d) > (1.0f + growth) * deformer.Plan().RebuiltCost(d);
        }
        return rebuilds;
    };
    const std::vector<int> first = run();
    EXPECT_FALSE(first.empty()) << "a strong twist should degrade the refit tree";
    EXPECT_EQ(first, run());
}

RenderSettings Small() {
    RenderSettings s;
    s.width = 96;
    s.height = 72;
    s.maxDepth = 2;
    return s;
}

// The frame renderer's image of the deformed sphere equals a one-shot image of a static BLAS
// built from the same deformed triangles (another tree, the same closest hits).
TEST(CpuFrameRenderer, ImageOfADeformedMeshEqualsAStaticBuildOfItsTriangles) {
    DeformingScene s(Wave(0.3f));
    s.At(0.9f);
    const Image rest = RenderRaw(s.scene, Small());  // the scene's own TLAS: the rest sphere
    auto renderer = MakeFrameRenderer(Backend::kCpu, s.scene);
    renderer->Update(s.scene, {{}, false, {}});
    Image deformed;
    renderer->Trace(s.scene, Small(), &deformed);
    EXPECT_EQ(renderer->Times().deformed, 0u);  // the constructor's update deformed it already

    CpuDeformer deformer;
    std::vector<BlasView> views = Views(s.scene);
    std::vector<Aabb> bounds = Bounds(s.scene);
    deformer.Update(s.scene, {}, views, bounds);
    const TriangleMesh mesh = RestMeshOfBlas(deformer.Snapshot(s.deformation)).rest;
    RenderScene still = s.scene;
    still.deformations.clear();
    still.blases[s.scene.deformations[s.deformation].blasId] =
        std::make_shared<const Blas>(BuildTriangleBlas(mesh));
    still.BuildTlas();
    const Image reference = RenderRaw(still, Small());
    ASSERT_EQ(deformed.pixels.size(), reference.pixels.size());
    uint32_t differing = 0;
    for (size_t i = 0; i < reference.pixels.size(); ++i)
        differing += glm::length(deformed.pixels[i] - reference.pixels[i]) > 1e-4f;
    EXPECT_LE(differing, reference.pixels.size() / 1000) << "pixels that differ";
    uint32_t moved = 0;
    for (size_t i = 0; i < rest.pixels.size(); ++i)
        moved += glm::length(deformed.pixels[i] - rest.pixels[i]) > 1e-2f;
    EXPECT_GT(moved, rest.pixels.size() / 20) << "the wave should change the image";
}

TEST(CpuFrameRenderer, ASceneWithoutDeformationsSpendsNothingOnThem) {
    RenderScene scene;
    const Sphere sphere{vec3(0.0f), 1.0f};
    scene.AddBlas(std::make_shared<const Blas>(BuildSphereBlas(std::span(&sphere, 1))));
    scene.AddMaterial(Material{});
    scene.AddInstance(0, 0, glm::mat4(1.0f));
    scene.camera.position = vec3(0, 0, 5);
    auto renderer = MakeFrameRenderer(Backend::kCpu, scene);
    const uint32_t moved = 0;
    renderer->Update(scene, {std::span(&moved, 1), false, {}});
    renderer->Trace(scene, Small(), nullptr);
    EXPECT_EQ(renderer->Times().deformed, 0u);
    EXPECT_EQ(renderer->Times().deformMs, 0.0);
    EXPECT_EQ(renderer->Times().blasMs, 0.0);
}

}  // namespace
}  // namespace rtrt
