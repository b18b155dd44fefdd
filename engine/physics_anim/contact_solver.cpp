#include "engine/physics_anim/contact_solver.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cmath>

#include "engine/core/parallel_for.h"

namespace rtrt::physics {

namespace {

// Below this many manifolds a step is solved on one thread: the threads' start costs more.
constexpr uint32_t kParallelManifolds = 1024;
// The smallest slice of a colour that a thread claims at once.
constexpr uint32_t kMinBlockManifolds = 32;
// Blocks per share: what is left for the other threads to take when one is behind.
constexpr uint32_t kBlocksPerShare = 4;

}  // namespace

void GatherSolverBodies(std::span<const SimBody> bodies, std::span<const uint32_t> slotOfBody,
                        std::span<SolverBody> out) {
    ParallelFor(0, bodies.size(), 1024, [&](size_t i) {
        const SimBody& s = bodies[i];
        SolverBody& b = out[slotOfBody[i]];
        b.velocity = s.velocity;
        b.angularVelocity = s.angularVelocity;
        b.invMass = s.awake ? s.invMass : 0.0f;
        b.invInertia = s.awake ? s.invInertiaWorld : glm::mat3(0.0f);
    });
}

void SolveContacts(std::span<const SimBody> bodies, std::span<const uint32_t> slotOfBody,
                   std::span<SolverBody> solverBodies, std::span<PseudoVelocity> pseudo,
                   std::span<Contact> contacts, const ContactBatches& batches,
                   const SolverSettings& settings, ContactSolverScratch& scratch) {
    const uint32_t colors = batches.Colors();
    if (colors == 0) return;
    // A stage is one pass over one colour. Each colour is cut into one share per thread, by
    // region when the batches have regions (else evenly), and each share into blocks. The
    // overflow colour is a single block, solved in order by one thread.
    ContactRows& rows = scratch.rows;
    rows.Build(contacts, bodies, slotOfBody, solverBodies, batches, settings);
    const int threads =
        batches.Manifolds() < kParallelManifolds ? 1 : StageRunner::AvailableThreads();
    const auto shareCount = static_cast<uint32_t>(threads);
    scratch.shares.clear();
    for (uint32_t color = 0; color < colors; ++color) {
        const uint32_t colorBegin = batches.colorBegin[color];
        const uint32_t colorEnd = batches.colorBegin[color + 1];
        const uint32_t manifolds = colorEnd - colorBegin;
        if (batches.lastIsOverflow && color + 1 == colors) {
            scratch.shares.push_back({colorBegin, colorEnd, std::max(1u, manifolds)});
            for (uint32_t s = 1; s < shareCount; ++s) {
                scratch.shares.push_back({colorEnd, colorEnd, 1});
            }
            continue;
        }
        // Shares and blocks start at the rows' groups.
        constexpr uint32_t kGroup = ContactRows::kGroupManifolds;
        const uint32_t blockSize =
            (std::max(kMinBlockManifolds, manifolds / (kBlocksPerShare * shareCount)) + kGroup -
             1) /
            kGroup * kGroup;
        for (uint32_t s = 0; s < shareCount; ++s) {
            uint32_t begin =
                colorBegin + static_cast<uint32_t>(uint64_t{manifolds} * s / shareCount);
            uint32_t end =
                colorBegin + static_cast<uint32_t>(uint64_t{manifolds} * (s + 1) / shareCount);
            if (batches.regions > 0) {
                begin = batches.RegionBegin(color, s * batches.regions / shareCount);
                end = batches.RegionBegin(color, (s + 1) * batches.regions / shareCount);
            }
            scratch.shares.push_back(
                {rows.GroupStart(color, begin), rows.GroupStart(color, end), blockSize});
        }
    }
    scratch.stages.clear();
    scratch.blocks.clear();
    const auto addPass = [&](RowPass pass, bool writeBack = false) {
        for (uint32_t color = 0; color < colors; ++color) {
            scratch.stages.push_back({pass, writeBack, color});
            for (uint32_t s = 0; s < shareCount; ++s) {
                const ContactSolverScratch::Share& share = scratch.shares[color * shareCount + s];
                scratch.blocks.push_back((share.end - share.begin + share.blockSize - 1) /
                                         share.blockSize);
            }
        }
    };
    // The position iterations read and write only pseudo velocities, which nothing else touches,
    // so they ride along with the first velocity iterations: the same arithmetic in fewer stages,
    // each contact read once for both.
    const int shared = std::min(settings.velocityIterations, settings.positionIterations);
    addPass(RowPass::kWarmStart);
    for (int i = 0; i < shared; ++i) addPass(RowPass::kVelocityAndPosition);
    for (int i = shared; i < settings.velocityIterations; ++i) addPass(RowPass::kVelocity);
    addPass(RowPass::kRestitution, true);  // the last pass that changes impulses
    for (int i = shared; i < settings.positionIterations; ++i) addPass(RowPass::kPosition);

    const float rate = settings.positionCorrection / settings.dt;
    scratch.runner.Run(scratch.blocks, threads, [&](size_t stageIndex, uint32_t s, uint32_t block) {
        const ContactSolverScratch::Stage& stage = scratch.stages[stageIndex];
        const ContactSolverScratch::Share& share = scratch.shares[stage.color * shareCount + s];
        const uint32_t first = share.begin + block * share.blockSize;
        const uint32_t last = std::min(share.end, first + share.blockSize);
        const uint32_t rowBegin = rows.RowBegin(stage.color, first);
        const uint32_t rowEnd = rows.RowBegin(stage.color, last);
        rows.Solve(solverBodies, pseudo, rowBegin, rowEnd, stage.pass, rate);
        if (stage.writeBack) rows.WriteBack(contacts, rowBegin, rowEnd);
    });
}

}  // namespace rtrt::physics
