// ContactRows: every contact in exactly one lane, a manifold's contacts in one lane in order, no
// moving body twice in a row, manifolds dealt so that a group's rows stay few, and the lanes'
// arithmetic against impulses worked out by hand.
#include "engine/physics_anim/contact_rows.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <numeric>
#include <set>
#include <vector>

#include "engine/physics_anim/contact_solver.h"

namespace rtrt::physics {
namespace {

constexpr float kDt = 1.0f / 120.0f;

SolverSettings Settings() { return {kDt, vec3(0.0f, -9.81f, 0.0f), 10, 4, 1.0f, 0.005f, 0.2f}; }

// Bodies 0..count-1, all moving unit spheres at rest unless changed.
struct Scene {
    std::vector<SimBody> bodies;
    std::vector<uint32_t> slots;
    std::vector<SolverBody> solverBodies;
    std::vector<BodyAtStart> starts;
    std::vector<PseudoVelocity> pseudo;
    std::vector<Contact> contacts;
    ContactBatches batches;

    explicit Scene(uint32_t count) : bodies(count), slots(count) {
        std::iota(slots.begin(), slots.end(), 0u);
        for (SimBody& b : bodies) {
            b.dynamic = b.awake = true;
            b.invMass = 1.0f;
            b.invInertiaWorld = glm::mat3(2.5f);
        }
    }
    void AddManifold(uint32_t a, uint32_t b, int points) {
        for (int k = 0; k < points; ++k) {
            contacts.push_back({a, b, vec3(0.0f, 1.0f, 0.0f), vec3(0.1f * float(k), 0.0f, 0.0f),
                                0.0f, 0.0f, 0.0f, 0.0f, 0.0f});
        }
        batches.manifoldBegin.push_back(static_cast<uint32_t>(contacts.size()));
    }
    void EndColor() { batches.colorBegin.push_back(batches.Manifolds()); }
    void Build(ContactRows& rows) {
        solverBodies.resize(bodies.size());
        starts.resize(bodies.size());
        pseudo.resize(bodies.size());
        tbb::affinity_partitioner affinity;
        GatherSolverBodies(bodies, slots, solverBodies, starts, pseudo, affinity);
        rows.Build(contacts, slots, starts, solverBodies, batches, Settings());
    }
};

TEST(ContactRowsTest, EveryContactInOneLaneInOrderAndNoMovingBodyTwiceInARow) {
    Scene scene(400);
    for (uint32_t i = 0; i < 70; ++i) scene.AddManifold(2 * i, 2 * i + 1, int(i * 5 % 8) + 1);
    scene.EndColor();
    for (uint32_t i = 0; i < 40; ++i) scene.AddManifold(200 + i, 300 + i, int(i % 3) + 1);
    scene.EndColor();
    for (uint32_t i = 0; i < 5; ++i) scene.AddManifold(0, 10 + i, 2);  // all share body 0
    scene.EndColor();
    scene.batches.lastIsOverflow = true;
    ContactRows rows;
    scene.Build(rows);

    std::map<uint32_t, std::pair<uint32_t, int>> placeOf;  // contact -> (row, lane)
    for (uint32_t r = 0; r < rows.Rows(); ++r) {
        const ContactRow& row = rows.Row(r);
        ASSERT_NE(row.activeLanes, 0u) << "row " << r;
        std::set<uint32_t> moving;
        for (int l = 0; l < kLanes; ++l) {
            if ((row.activeLanes >> l & 1u) == 0) continue;
            EXPECT_TRUE(placeOf.emplace(row.contact[l], std::make_pair(r, l)).second);
            EXPECT_TRUE(moving.insert(row.slotA[l]).second) << "row " << r;
            EXPECT_TRUE(moving.insert(row.slotB[l]).second) << "row " << r;
        }
    }
    ASSERT_EQ(placeOf.size(), scene.contacts.size());
    const ContactBatches& b = scene.batches;
    for (uint32_t color = 0; color < b.Colors(); ++color) {
        const uint32_t rowBegin = rows.RowBegin(color, b.colorBegin[color]);
        const uint32_t rowEnd = rows.RowBegin(color, b.colorBegin[color + 1]);
        for (uint32_t m = b.colorBegin[color]; m < b.colorBegin[color + 1]; ++m) {
            const auto [firstRow, lane] = placeOf[b.manifoldBegin[m]];
            for (uint32_t k = b.manifoldBegin[m]; k < b.manifoldBegin[m + 1]; ++k) {
                const auto [row, l] = placeOf[k];
                EXPECT_EQ(l, lane) << "contact " << k;
                EXPECT_EQ(row, firstRow + (k - b.manifoldBegin[m])) << "contact " << k;
                EXPECT_GE(row, rowBegin);
                EXPECT_LT(row, rowEnd);
            }
        }
    }
    // The overflow's manifolds share body 0: one lane per row, in order.
    for (uint32_t r = rows.RowBegin(2, b.colorBegin[2]); r < rows.Rows(); ++r) {
        EXPECT_EQ(rows.Row(r).activeLanes, 1u);
        EXPECT_EQ(rows.Row(r).contact[0], scene.contacts.size() - (rows.Rows() - r));
    }
}

TEST(ContactRowsTest, ManifoldsWithMostContactsAreDealtFirst) {
    // 31 one-contact manifolds, then one of eight: in order, the eight-contact one would land on
    // a lane that already holds four (12 rows); dealt largest first it has a lane of its own.
    Scene scene(64);
    for (uint32_t i = 0; i < 31; ++i) scene.AddManifold(2 * i, 2 * i + 1, 1);
    scene.AddManifold(62, 63, 8);
    scene.EndColor();
    ContactRows rows;
    scene.Build(rows);
    EXPECT_EQ(rows.Rows(), 8u);
}

// The solver fills rows block by block (Plan, then Fill of group-aligned ranges, in any order):
// the same rows, byte for byte, as Build.
TEST(ContactRowsTest, FillingBlocksInAnyOrderGivesBuildsRows) {
    Scene scene(400);
    for (uint32_t i = 0; i < 100; ++i) scene.AddManifold(2 * i, 2 * i + 1, int(i * 3 % 8) + 1);
    scene.EndColor();
    for (uint32_t i = 0; i < 50; ++i) scene.AddManifold(200 + i, 300 + i, int(i % 4) + 1);
    scene.EndColor();
    for (uint32_t k = 0; k < scene.contacts.size(); ++k) {
        scene.contacts[k].normalImpulse = 0.5f + 0.01f * float(k);
        scene.contacts[k].separation = 0.02f - 0.001f * float(k % 40);
    }
    ContactRows built;
    scene.Build(built);
    ContactRows planned;
    const SolverSettings settings = Settings();  // Plan keeps its inputs for Fill
    planned.Plan(scene.contacts, scene.slots, scene.starts, scene.solverBodies, scene.batches,
                 settings);
    ASSERT_EQ(planned.Rows(), built.Rows());
    // Blocks of two groups each (and what is left), filled last first.
    const ContactBatches& b = scene.batches;
    std::vector<std::pair<uint32_t, uint32_t>> blocks;
    for (uint32_t color = 0; color < b.Colors(); ++color) {
        for (uint32_t m = b.colorBegin[color]; m < b.colorBegin[color + 1];
             m += 2 * ContactRows::kGroupManifolds) {
            const uint32_t end =
                std::min(b.colorBegin[color + 1], m + 2 * ContactRows::kGroupManifolds);
            blocks.emplace_back(planned.RowBegin(color, m), planned.RowBegin(color, end));
        }
    }
    ASSERT_GT(blocks.size(), 2u);
    for (auto block = blocks.rbegin(); block != blocks.rend(); ++block) {
        planned.Fill(block->first, block->second);
    }
    for (uint32_t r = 0; r < built.Rows(); ++r) {
        EXPECT_EQ(std::memcmp(&planned.Row(r), &built.Row(r), sizeof(ContactRow)), 0)
            << "row " << r;
    }
}

TEST(ContactRowsTest, NormalImpulseStopsABodyOrLetsItCloseItsGap) {
    // Bodies 0 and 2 are static ground; 1 and 3 (mass 2) fall at 3 m/s onto them, the contact
    // point straight below the centre (no turn). Touching: the impulse 2 * 3 stops body 1.
    // Speculative, 1 cm apart: body 3 may still close the gap within the step, at 0.01 / dt.
    Scene scene(4);
    for (const uint32_t ground : {0u, 2u}) {
        scene.bodies[ground].dynamic = scene.bodies[ground].awake = false;
        scene.bodies[ground].invMass = 0.0f;
    }
    for (const uint32_t body : {1u, 3u}) {
        scene.bodies[body].invMass = 0.5f;
        scene.bodies[body].position = vec3(0.0f, 1.0f, 0.0f);
        scene.bodies[body].velocity = scene.bodies[body].startVelocity = vec3(0.0f, -3.0f, 0.0f);
    }
    scene.AddManifold(0, 1, 1);
    scene.AddManifold(2, 3, 1);
    scene.contacts[1].separation = 0.01f;
    scene.EndColor();
    ContactRows rows;
    scene.Build(rows);
    ASSERT_EQ(rows.Rows(), 1u);
    std::vector<PseudoVelocity> pseudo(4);
    rows.Solve(scene.solverBodies, pseudo, 0, 1, RowPass::kVelocity, 0.0f);
    rows.WriteBack(scene.contacts, 0, 1);
    EXPECT_NEAR(scene.contacts[0].normalImpulse, 6.0f, 1e-5f);
    EXPECT_NEAR(scene.solverBodies[1].velocity.y, 0.0f, 1e-5f);
    EXPECT_NEAR(scene.contacts[1].normalImpulse, 2.0f * (3.0f - 0.01f / kDt), 1e-4f);
    EXPECT_NEAR(scene.solverBodies[3].velocity.y, -0.01f / kDt, 1e-4f);
    // The ground did not move, and nothing turned.
    EXPECT_EQ(scene.solverBodies[0].velocity, vec3(0.0f));
    EXPECT_EQ(scene.solverBodies[1].angularVelocity, vec3(0.0f));
}

}  // namespace
}  // namespace rtrt::physics
