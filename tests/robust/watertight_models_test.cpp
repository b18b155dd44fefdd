// Watertightness on the real models (CPU; skipped when the models are not fetched): the Newell
// teapot tessellated from its 32 patches (game/assets/teapot.h) and dragon res4. Neither is closed
// (the teapot's spout and the scan's holes are open), so the expectation is local: a ray aimed at a
// point p of the surface away from open boundaries (a point of an edge used by exactly two
// triangles, wound consistently; shared by position, so patch seams count when their vertices
// agree bit for bit; or a vertex on such edges only), crossing the surface there (its direction
// within 60 degrees of every adjacent triangle's normal as wound, from either side, so it cannot
// graze a silhouette or a fold), hits the surface no later
// than p: t <= 1 + 1e-4 with dir = p - origin. A crack in the mesh or in the triangle test would
// let it through. The BVH's t must equal brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <optional>
#include <random>

#include "game/assets/mesh_io.h"
#include "game/assets/teapot.h"
#include "tests/robust/cpu_runner.h"
#include "tests/robust/scene_builder.h"
#include "tests/robust/traversal_checks.h"
#include "tests/test_util.h"

namespace rtrt::robust {
namespace {

struct PositionLess {
    bool operator()(vec3 a, vec3 b) const {
        return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    }
};

struct EdgeLess {
    bool operator()(const std::pair<vec3, vec3>& a, const std::pair<vec3, vec3>& b) const {
        PositionLess less;
        if (less(a.first, b.first)) return true;
        if (less(b.first, a.first)) return false;
        return less(a.second, b.second);
    }
};

// A direction within 60 degrees of every adjacent triangle's normal (the normals as wound), or
// nothing: a ray along it crosses the surface at the point. Normals of a consistently wound
// surface agree in sign where it crosses; a fold or a ridge seen edge-on does not qualify.
std::optional<vec3> CrossingDirection(const std::vector<vec3>& normals) {
    vec3 sum(0.0f);
    for (vec3 n : normals) sum += n;
    if (glm::length(sum) == 0.0f) return std::nullopt;
    const vec3 d = glm::normalize(sum);
    for (vec3 n : normals)
        if (glm::dot(n, d) < 0.5f) return std::nullopt;
    return d;
}

void ExpectRaysAtSharedPointsHit(const TriangleMesh& mesh, uint32_t maxTargets,
                                 uint32_t minShared) {
    // Triangle normals around each welded edge and vertex (positions compared bit for bit).
    struct EdgeUse {
        std::vector<vec3> normals;
        int direction = 0;  // +1 per use from the smaller to the larger end, -1 the other way
    };
    std::map<std::pair<vec3, vec3>, EdgeUse, EdgeLess> edges;
    std::map<vec3, std::vector<vec3>, PositionLess> vertices;
    for (const glm::uvec3& t : mesh.indices) {
        const vec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
        const vec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
        if (glm::length(cross) == 0.0f) continue;  // degenerate: no area to hit
        const vec3 n = glm::normalize(cross);
        for (int e = 0; e < 3; ++e) {
            vec3 a = p[e], b = p[(e + 1) % 3];
            const bool forward = PositionLess{}(a, b);
            if (!forward) std::swap(a, b);
            EdgeUse& use = edges[{a, b}];
            use.normals.push_back(n);
            use.direction += forward ? 1 : -1;
            vertices[p[e]].push_back(n);
        }
    }
    // Targets: points of manifold, consistently wound edges (two triangles using the edge in
    // opposite directions) and vertices on no other kind of edge, with a crossing direction.
    auto manifold = [](const EdgeUse& use) {
        return use.normals.size() == 2 && use.direction == 0;
    };
    std::map<vec3, bool, PositionLess> onOtherEdge;
    for (const auto& [edge, use] : edges)
        for (vec3 v : {edge.first, edge.second}) onOtherEdge[v] |= !manifold(use);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<std::pair<vec3, vec3>> targets;  // point, direction toward it
    uint32_t shared = 0;
    for (const auto& [edge, use] : edges) {
        if (!manifold(use)) continue;
        ++shared;
        if (const auto d = CrossingDirection(use.normals))
            for (float s : {0.5f, u(rng)})
                targets.push_back({edge.first + s * (edge.second - edge.first), *d});
    }
    for (const auto& [v, normals] : vertices)
        if (!onOtherEdge[v])
            if (const auto d = CrossingDirection(normals)) targets.push_back({v, *d});
    ASSERT_GE(shared, minShared) << "the mesh should be mostly welded";
    ::testing::Test::RecordProperty("edges", int(edges.size()));
    ::testing::Test::RecordProperty("manifold_edges", int(shared));
    ::testing::Test::RecordProperty("targets", int(targets.size()));
    std::shuffle(targets.begin(), targets.end(), rng);
    if (targets.size() > maxTargets) targets.resize(maxTargets);

    RenderScene scene;
    scene.AddMaterial({});
    scene.AddInstance(AddMeshBlas(scene, mesh), 0, glm::mat4(1.0f));
    scene.BuildTlas();
    const float size = MaxComponent(mesh.Bounds().Extent());
    std::vector<Ray> rays;
    for (const auto& [p, d] : targets) {
        // From either side, tilted by up to ~0.3 rad so the rays are not all along the normal.
        const vec3 dir = glm::normalize(d + 0.3f * (vec3(u(rng), u(rng), u(rng)) - 0.5f));
        const vec3 o = p + (u(rng) < 0.5f ? 0.3f : -0.3f) * size * dir;
        rays.push_back({o, kInfinity, p - o, 0});
    }
    const std::vector<SceneResult> results = CpuRunner{}.Scene(scene, rays);
    uint32_t through = 0;
    for (size_t i = 0; i < rays.size(); ++i)
        if ((!results[i].hit || results[i].t > 1.0f + 1e-4f) && ++through <= 5)
            ADD_FAILURE() << "ray " << i << " at a shared point passed it: hit " << results[i].hit
                          << " t " << results[i].t;
    EXPECT_EQ(through, 0u) << "of " << rays.size() << " rays";
    ExpectSameAsBruteForce(rays, results);
}

TEST(WatertightModels, TeapotRaysAtSharedVerticesAndEdgesHit) {
    RTRT_REQUIRE_MODEL(path, "teapot.inc");
    ExpectRaysAtSharedPointsHit(TessellateTeapot(path, 6), 20000, 2000);
}

TEST(WatertightModels, DragonRaysAtSharedVerticesAndEdgesHit) {
    RTRT_REQUIRE_MODEL(path, "dragon_vrip_res4.ply.gz");
    ExpectRaysAtSharedPointsHit(LoadMesh(path), 8000, 10000);
}

}  // namespace
}  // namespace rtrt::robust
