// ContactRows: every contact in exactly one lane, a manifold's contacts in one lane in order, no
// moving body twice in a row, manifolds dealt so that a group's rows stay few, and the lanes'
// arithmetic against impulses worked out by hand.
#include "engine/physics_anim/contact_rows.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "engine/physics_anim/contact_setup.h"
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
        for (size_t i = 0; i < bodies.size(); ++i) {
            GatherSolverBody(bodies[i], slots[i], solverBodies, starts, pseudo);
        }
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

glm::mat3 Diagonal(vec3 d) {
    glm::mat3 m(0.0f);
    for (int i = 0; i < 3; ++i) m[i][i] = d[i];
    return m;
}

// The rows set up eight contacts at once: each active lane holds exactly the bits that
// SetUpContact (contact_setup.h, which the GPU solver uses) gives for its contact, over bodies of
// every kind of inertia, resting and approaching, rolling and not; inactive lanes hold zeros.
TEST(ContactRowsTest, LanesHoldSetUpContactsBitsForEveryContact) {
    Scene scene(300);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const auto randomVector = [&] { return vec3(unit(random), unit(random), unit(random)); };
    for (uint32_t i = 0; i < scene.bodies.size(); ++i) {
        SimBody& body = scene.bodies[i];
        body.position = 3.0f * randomVector();
        body.velocity = body.startVelocity = randomVector();
        body.angularVelocity = body.startAngularVelocity = 2.0f * randomVector();
        body.friction = 0.5f + 0.5f * unit(random);
        body.restitution = 0.5f + 0.5f * unit(random);
        const glm::mat3 turn = glm::mat3_cast(glm::normalize(glm::quat(0.5f, randomVector())));
        body.invInertiaWorld = turn * Diagonal(vec3(1.5f) + randomVector()) * glm::transpose(turn);
        if (i % 7 == 0) body.invInertiaWorld = glm::mat3(0.0f);  // fixed rotation
        if (i % 11 == 0) body.awake = false;  // does not move: zero inverse mass and inertia
    }
    for (uint32_t i = 0; i + 1 < scene.bodies.size(); i += 2) {
        const int points = int(i * 5 % 8) + 1;
        for (int k = 0; k < points; ++k) {
            const vec3 normal = glm::normalize(randomVector() + vec3(0.0f, 0.01f, 0.0f));
            const float separation = 0.05f * unit(random);
            const float rolling = i % 10 == 4 ? 0.02f : 0.0f;  // rows without one too
            scene.contacts.push_back({i, i + 1, normal, scene.bodies[i].position + randomVector(),
                                      separation, rolling, unit(random) + 1.0f, 0.1f * unit(random),
                                      0.1f * unit(random)});
        }
        scene.batches.manifoldBegin.push_back(static_cast<uint32_t>(scene.contacts.size()));
    }
    scene.EndColor();
    // Rows are reused from step to step: a first build in which every contact rolls, and passes
    // over it, leave rolling lanes and impulses everywhere.
    const std::vector<Contact> contacts = scene.contacts;
    for (Contact& c : scene.contacts) c.rollingLimit = 0.03f;
    ContactRows rows;
    scene.Build(rows);
    for (const RowPass pass : {RowPass::kWarmStart, RowPass::kVelocityAndPosition}) {
        rows.Solve(scene.solverBodies, scene.pseudo, 0, rows.Rows(), pass, 10.0f);
    }
    scene.contacts = contacts;
    scene.Build(rows);
    const auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    uint32_t rolled = 0;
    uint32_t bounced = 0;
    for (uint32_t r = 0; r < rows.Rows(); ++r) {
        const ContactRow& row = rows.Row(r);
        bool rowRolls = false;
        for (int l = 0; l < kLanes; ++l) {
            if ((row.activeLanes >> l & 1u) == 0) {
                // Zero in every float, so the passes' work on the lane changes nothing.
                for (const Lanes* lanes :
                     {&row.normal.x,      &row.normal.y,        &row.normal.z,
                      &row.tangent1.x,    &row.tangent1.y,      &row.tangent1.z,
                      &row.tangent2.x,    &row.tangent2.y,      &row.tangent2.z,
                      &row.anchorA.x,     &row.anchorA.y,       &row.anchorA.z,
                      &row.anchorB.x,     &row.anchorB.y,       &row.anchorB.z,
                      &row.normalMass,    &row.tangentMass1,    &row.tangentMass2,
                      &row.normalImpulse, &row.tangentImpulse1, &row.tangentImpulse2,
                      &row.friction,      &row.allowedApproach, &row.bounce,
                      &row.overlap,       &row.pseudoImpulse}) {
                    EXPECT_EQ((*lanes)[l], 0.0f) << "row " << r << " lane " << l;
                }
                continue;
            }
            const Contact& c = scene.contacts[row.contact[l]];
            const ContactSetUp want = SetUpContact(
                c, scene.starts[row.slotA[l]], scene.starts[row.slotB[l]],
                scene.solverBodies[row.slotA[l]], scene.solverBodies[row.slotB[l]], Settings());
            const auto lane3 = [&](const Lanes3& v) { return vec3(v.x[l], v.y[l], v.z[l]); };
            const auto same3 = [&](vec3 a, vec3 b) {
                return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z);
            };
            SCOPED_TRACE("contact " + std::to_string(row.contact[l]));
            EXPECT_TRUE(same3(lane3(row.normal), c.normal));
            EXPECT_TRUE(same3(lane3(row.tangent1), want.tangent1));
            EXPECT_TRUE(same3(lane3(row.tangent2), want.tangent2));
            EXPECT_TRUE(same3(lane3(row.anchorA), want.anchorA));
            EXPECT_TRUE(same3(lane3(row.anchorB), want.anchorB));
            EXPECT_TRUE(same(row.normalMass[l], want.normalMass));
            EXPECT_TRUE(same(row.tangentMass1[l], want.tangentMass1));
            EXPECT_TRUE(same(row.tangentMass2[l], want.tangentMass2));
            EXPECT_TRUE(same(row.friction[l], want.friction));
            EXPECT_TRUE(same(row.allowedApproach[l], want.allowedApproach));
            EXPECT_TRUE(same(row.overlap[l], want.overlap));
            EXPECT_TRUE(same(row.bounce[l], want.bounce));
            EXPECT_TRUE(same(row.normalImpulse[l], c.normalImpulse));
            EXPECT_TRUE(same(row.tangentImpulse1[l], c.tangentImpulse1));
            EXPECT_TRUE(same(row.tangentImpulse2[l], c.tangentImpulse2));
            EXPECT_EQ(row.pseudoImpulse[l], 0.0f);
            bounced += want.bounce > 0.0f ? 1 : 0;
            if (want.rollingLimit > 0.0f) {
                ++rolled;
                rowRolls = true;
                ASSERT_TRUE(row.rolling);
                const RollingLanes& rolling = rows.Rolling(r);
                EXPECT_TRUE(same(rolling.limit[l], want.rollingLimit));
                EXPECT_EQ(rolling.impulse.x[l], 0.0f);
                EXPECT_EQ(rolling.impulse.y[l], 0.0f);
                EXPECT_EQ(rolling.impulse.z[l], 0.0f);
                for (int i = 0; i < 3; ++i) {
                    EXPECT_TRUE(same3(lane3(rolling.mass.column[i]), want.rollingMass[i]));
                }
            } else if (row.rolling) {
                EXPECT_EQ(rows.Rolling(r).limit[l], 0.0f);
            }
        }
        EXPECT_EQ(row.rolling, rowRolls) << "row " << r;
    }
    EXPECT_GT(rolled, 50u);
    EXPECT_GT(bounced, 50u);
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
