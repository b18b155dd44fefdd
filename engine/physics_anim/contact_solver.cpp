#include "engine/physics_anim/contact_solver.h"

#include <algorithm>
#include <cmath>

namespace rtrt::physics {

namespace {

// Below this many manifolds a step is solved on one thread: the threads' start costs more.
constexpr uint32_t kParallelManifolds = 1024;
// The smallest slice of a colour that a thread claims at once.
constexpr uint32_t kMinBlockManifolds = 32;
// Blocks per share: what is left for the other threads to take when one is behind.
constexpr uint32_t kBlocksPerShare = 4;
// Colours with fewer manifolds than this are solved in runs of at most kSmallSpanManifolds, one
// thread per run.
constexpr uint32_t kSmallColorManifolds = 256;
constexpr uint32_t kSmallSpanManifolds = 512;

// Cuts the colours into stages' spans, and each span into one share per thread and each share
// into blocks of rows. A colour of many manifolds is a span of its own, cut into shares of equal
// rows in layout (region) order; a run of small colours is one span of one block,
// solved by one thread in colour order: the same arithmetic in the same order as one stage per
// colour, without a stage's wait for every thread. The overflow colour is always in such a run.
void PlanBlocks(const ContactBatches& batches, const ContactRows& rows, uint32_t shareCount,
                ContactSolverScratch& scratch) {
    const uint32_t colors = batches.Colors();
    const auto manifoldsOf = [&](uint32_t color) {
        return batches.colorBegin[color + 1] - batches.colorBegin[color];
    };
    const auto small = [&](uint32_t color) {
        return manifoldsOf(color) < kSmallColorManifolds ||
               (batches.lastIsOverflow && color + 1 == colors);
    };
    scratch.spans.clear();
    for (uint32_t color = 0; color < colors;) {
        uint32_t last = color;
        if (small(color)) {
            uint32_t total = manifoldsOf(color);
            while (last + 1 < colors && small(last + 1) &&
                   total + manifoldsOf(last + 1) <= kSmallSpanManifolds) {
                total += manifoldsOf(++last);
            }
        }
        scratch.spans.push_back({color, last});
        color = last + 1;
    }
    scratch.firstBlock.assign(1, 0);
    scratch.blockRows.clear();
    const auto addBlocks = [&](uint32_t color, uint32_t begin, uint32_t end, uint32_t blockSize) {
        for (uint32_t first = begin; first < end; first += blockSize) {
            const uint32_t last = std::min(end, first + blockSize);
            scratch.blockRows.push_back({rows.RowBegin(color, first), rows.RowBegin(color, last)});
        }
        scratch.firstBlock.push_back(static_cast<uint32_t>(scratch.blockRows.size()));
    };
    for (const ContactSolverScratch::Span& span : scratch.spans) {
        const uint32_t color = span.firstColor;
        const uint32_t colorBegin = batches.colorBegin[color];
        const uint32_t colorEnd = batches.colorBegin[color + 1];
        if (span.lastColor != color || small(color)) {
            const uint32_t rowBegin = rows.RowBegin(color, colorBegin);
            const uint32_t rowEnd =
                rows.RowBegin(span.lastColor, batches.colorBegin[span.lastColor + 1]);
            scratch.blockRows.push_back({rowBegin, rowEnd});
            scratch.firstBlock.push_back(static_cast<uint32_t>(scratch.blockRows.size()));
            for (uint32_t s = 1; s < shareCount; ++s) {
                scratch.firstBlock.push_back(scratch.firstBlock.back());
            }
            continue;
        }
        // Shares and blocks start at the rows' groups.
        const uint32_t manifolds = colorEnd - colorBegin;
        constexpr uint32_t kGroup = ContactRows::kGroupManifolds;
        const uint32_t blockSize =
            (std::max(kMinBlockManifolds, manifolds / (kBlocksPerShare * shareCount)) + kGroup -
             1) /
            kGroup * kGroup;
        // Shares of equal rows (the passes' work), in layout order: the manifolds are laid out
        // region by region, so a share still covers about the same stretch of the floor in every
        // colour, and a body's cache line mostly stays with one core.
        const uint32_t firstRow = rows.RowBegin(color, colorBegin);
        const uint32_t endRow = rows.RowBegin(color, rows.GroupStart(color, colorEnd));
        const auto shareStart = [&](uint32_t s) {
            if (s == 0) return colorBegin;
            const uint64_t target = firstRow + uint64_t{endRow - firstRow} * s / shareCount;
            uint32_t low = colorBegin, high = colorEnd;  // the first manifold whose group
            while (low < high) {                         // starts at or after the target row
                const uint32_t middle = low + (high - low) / 2;
                if (rows.RowBegin(color, rows.GroupStart(color, middle)) >= target) {
                    high = middle;
                } else {
                    low = middle + 1;
                }
            }
            return low;
        };
        for (uint32_t s = 0; s < shareCount; ++s) {
            const uint32_t begin = shareStart(s);
            const uint32_t end = s + 1 == shareCount ? colorEnd : shareStart(s + 1);
            addBlocks(color, rows.GroupStart(color, begin), rows.GroupStart(color, end), blockSize);
        }
    }
}

}  // namespace

void SolveContacts(std::span<const uint32_t> slotOfBody, std::span<const BodyAtStart> starts,
                   std::span<SolverBody> solverBodies, std::span<PseudoVelocity> pseudo,
                   std::span<Contact> contacts, const ContactBatches& batches,
                   const SolverSettings& settings, ContactSolverScratch& scratch) {
    const uint32_t colors = batches.Colors();
    if (colors == 0) return;
    ContactRows& rows = scratch.rows;
    rows.Plan(contacts, slotOfBody, starts, solverBodies, batches, settings);
    const int threads =
        batches.Manifolds() < kParallelManifolds ? 1 : StageRunner::AvailableThreads();
    const auto shareCount = static_cast<uint32_t>(threads);
    PlanBlocks(batches, rows, shareCount, scratch);
    scratch.stages.clear();
    scratch.blocks.clear();
    const auto addPass = [&](RowPass pass, bool writeBack = false) {
        for (uint32_t span = 0; span < scratch.spans.size(); ++span) {
            scratch.stages.push_back({pass, writeBack, span});
            for (uint32_t s = 0; s < shareCount; ++s) {
                const uint32_t at = span * shareCount + s;
                scratch.blocks.push_back(scratch.firstBlock[at + 1] - scratch.firstBlock[at]);
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
        const ContactSolverScratch::Block& rowsOf =
            scratch.blockRows[scratch.firstBlock[stage.span * shareCount + s] + block];
        if (stage.pass == RowPass::kWarmStart) rows.Fill(rowsOf.rowBegin, rowsOf.rowEnd);
        rows.Solve(solverBodies, pseudo, rowsOf.rowBegin, rowsOf.rowEnd, stage.pass, rate);
        if (stage.writeBack) rows.WriteBack(contacts, rowsOf.rowBegin, rowsOf.rowEnd);
    });
}

}  // namespace rtrt::physics
