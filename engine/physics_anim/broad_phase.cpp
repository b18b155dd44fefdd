#include "engine/physics_anim/broad_phase.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>

#include "engine/core/parallel_for.h"
#include "engine/physics_anim/lanes.h"

namespace rtrt::physics {

namespace {

// The spread of the box centres (sums in double: many boxes far from the origin would lose the
// variance to cancellation in float) and the bounds of all boxes, in one parallel pass. The
// deterministic reduce cuts the boxes the same way on any number of threads, so the sums are
// the same bits.
struct Spread {
    double sum[3] = {0.0, 0.0, 0.0};
    double sumSquares[3] = {0.0, 0.0, 0.0};
    vec3 low{std::numeric_limits<float>::infinity()};
    vec3 high{-std::numeric_limits<float>::infinity()};
};

Spread SpreadOf(std::span<const BroadPhaseBox> boxes) {
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<size_t>(0, boxes.size(), 2048), Spread{},
        [&](const tbb::blocked_range<size_t>& r, Spread s) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const BroadPhaseBox& box = boxes[i];
                for (int k = 0; k < 3; ++k) {
                    const double c = 0.5 * (static_cast<double>(box.min[k]) + box.max[k]);
                    s.sum[k] += c;
                    s.sumSquares[k] += c * c;
                }
                s.low = glm::min(s.low, box.min);
                s.high = glm::max(s.high, box.max);
            }
            return s;
        },
        [](Spread a, const Spread& b) {
            for (int k = 0; k < 3; ++k) {
                a.sum[k] += b.sum[k];
                a.sumSquares[k] += b.sumSquares[k];
            }
            a.low = glm::min(a.low, b.low);
            a.high = glm::max(a.high, b.high);
            return a;
        });
}

// The axes ordered by the variance of the box centres, largest first.
std::array<int, 3> AxesBySpread(const Spread& spread, size_t boxes) {
    const auto n = static_cast<double>(boxes);
    double variance[3];
    for (int k = 0; k < 3; ++k) {
        variance[k] = spread.sumSquares[k] / n - (spread.sum[k] / n) * (spread.sum[k] / n);
    }
    std::array<int, 3> axes{0, 1, 2};
    std::stable_sort(axes.begin(), axes.end(),
                     [&](int a, int b) { return variance[a] > variance[b]; });
    return axes;
}

// Sorts [begin, end) by insertion, giving up (false, entries still a permutation) after maxShifts
// moves.
template <typename Entry, typename Before>
bool SortRangeByInsertion(Entry* begin, Entry* end, size_t maxShifts, const Before& before) {
    size_t shifts = 0;
    for (Entry* i = begin + 1; i < end; ++i) {
        const Entry entry = *i;
        Entry* j = i;
        for (; j > begin && before(entry, *(j - 1)); --j) *j = *(j - 1);
        *j = entry;
        shifts += static_cast<size_t>(i - j);
        if (shifts > maxShifts) return false;
    }
    return true;
}

// Refreshes each entry (refresh(entry): its new key), then sorts by insertion, in chunks at once,
// giving up (false, entries still a permutation) after about maxShifts moves. Each chunk is
// refreshed and sorted on its own; then, chunk by chunk, the entries that belong before the end of
// the sorted entries ahead of the chunk (few, when the entries were nearly sorted) are inserted
// among them. An entry that moved far forward is carried through every chunk after it, and the
// joining then costs what one serial insertion sort would. before is a strict total order, so the
// result is the one sorted order, whatever the chunks and threads.
template <typename Entry, typename Refresh, typename Before>
bool RefreshAndSortByInsertion(std::vector<Entry>& entries, size_t maxShifts,
                               const Refresh& refresh, const Before& before) {
    constexpr size_t kChunk = 1024;
    const size_t n = entries.size();
    const size_t chunks = (n + kChunk - 1) / kChunk;
    Entry* const data = entries.data();
    if (chunks <= 1) {
        for (Entry& entry : entries) refresh(entry);
        return SortRangeByInsertion(data, data + n, maxShifts, before);
    }
    const size_t chunkShifts = maxShifts / chunks;
    std::atomic<bool> sorted = true;
    ParallelFor(0, chunks, 1, [&](size_t c) {
        Entry* const begin = data + c * kChunk;
        Entry* const end = data + std::min(n, (c + 1) * kChunk);
        for (Entry* entry = begin; entry < end; ++entry) refresh(*entry);
        if (!SortRangeByInsertion(begin, end, chunkShifts, before)) {
            sorted.store(false, std::memory_order_relaxed);
        }
    });
    if (!sorted.load()) return false;
    size_t shifts = 0;
    for (size_t c = 1; c < chunks; ++c) {
        const size_t start = c * kChunk;
        const Entry last = data[start - 1];  // the largest of the sorted entries ahead
        for (size_t i = start; i < std::min(n, start + kChunk) && before(data[i], last); ++i) {
            const Entry entry = data[i];
            size_t j = i;
            for (; j > 0 && before(entry, data[j - 1]); --j) data[j] = data[j - 1];
            data[j] = entry;
            shifts += i - j;
            if (shifts > maxShifts) return false;
        }
    }
    return true;
}

// The insertion sort's budget: beyond it, the order has changed too much since the last step.
constexpr size_t kMaxInsertionShiftsPerBox = 8;

// Strips of at least this many boxes on average: fewer would cost more in bookkeeping than
// they save in tests.
constexpr size_t kMinBoxesPerStrip = 16;
constexpr uint32_t kMaxStrips = 4096;
// A layout whose boxes span more than this many strips each on average (many boxes much
// larger than the typical one) falls back to one strip.
constexpr size_t kMaxStripsPerBox = 4;
// The strip width comes from the median extent of this many boxes at most.
constexpr size_t kWidthSamples = 1024;
// The strip dealing's chunks of the sweep order: few enough that their per-strip counts stay
// small, large enough to be worth a task.
constexpr size_t kMinDealChunk = 256;
constexpr size_t kMaxDealChunks = 64;

}  // namespace

bool SweepAndPrune::FindPairs(std::span<const BroadPhaseBox> boxes,
                              std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                              std::span<const uint32_t> names) {
    pairs.clear();
    found_ = 0;
    if (boxes.size() < 2) {
        order_.assign(boxes.size(), {0.0f, 0});
        return true;
    }
    const Spread spread = SpreadOf(boxes);
    const std::array<int, 3> axes = AxesBySpread(spread, boxes.size());
    const int axis = axes[0];
    const int stripAxis = axes[1];
    const int other2 = axes[2];
    // Ties broken by index, so the order (and the pairs' order) never depends on the sort. Last
    // step's order is a permutation of the same boxes when their number and the axis have not
    // changed, and bodies move little in a step: sorting by insertion from it takes about n
    // steps. When it would take many more, a full sort finishes the job.
    const auto before = [](const Entry& a, const Entry& b) {
        return a.min != b.min ? a.min < b.min : a.box < b.box;
    };
    const bool coherent = order_.size() == boxes.size() && axis == lastAxis_;
    lastAxis_ = axis;
    const auto refresh = [&](Entry& entry) { entry.min = boxes[entry.box].min[axis]; };
    if (!coherent || !RefreshAndSortByInsertion(order_, kMaxInsertionShiftsPerBox * order_.size(),
                                                refresh, before)) {
        if (!coherent) {
            order_.resize(boxes.size());
            for (uint32_t i = 0; i < boxes.size(); ++i) order_[i] = {boxes[i].min[axis], i};
        }
        tbb::parallel_sort(order_.begin(), order_.end(), before);
    }
    const Strips strips =
        PlanStrips(boxes, stripAxis, spread.low[stripAxis], spread.high[stripAxis]);
    DealIntoStrips(boxes, strips, axis, stripAxis, other2);
    // Each strip swept on its own, its pairs kept apart and joined in strip order: the same pairs
    // in the same order on any number of threads. Two boxes that share several strips are paired
    // only in the strip that holds the larger of their lower bounds on the strip axis.
    if (stripPairs_.size() < strips.count) stripPairs_.resize(strips.count);
    ParallelFor(0, strips.count, 1, [&](uint32_t strip) {
        stripPairs_[strip].clear();
        SweepStrip(strips, strip, stripPairs_[strip]);
    });
    pairStart_.assign(strips.count + 1, 0);
    for (uint32_t strip = 0; strip < strips.count; ++strip) {
        pairStart_[strip + 1] = pairStart_[strip] + stripPairs_[strip].size();
    }
    pairs.resize(pairStart_[strips.count]);
    ParallelFor(0, strips.count, 1, [&](uint32_t strip) {
        auto out = pairs.begin() + pairStart_[strip];
        if (names.empty()) {
            std::copy(stripPairs_[strip].begin(), stripPairs_[strip].end(), out);
            return;
        }
        for (const auto& [i, j] : stripPairs_[strip]) *out++ = {names[i], names[j]};
    });
    return found_ <= maxPairs_;
}

void SweepAndPrune::SweptBoxes::Resize(size_t n) {
    // Room for a full row of lanes read from the last box.
    const size_t padded = n + kLanes - 1;
    for (std::vector<float>* bound : {&min0, &max0, &min1, &max1, &min2, &max2}) {
        bound->resize(padded);
    }
    box.resize(padded);
    isStatic.resize(padded);
}

void SweepAndPrune::SweepStrip(const Strips& strips, uint32_t strip,
                               std::vector<std::pair<uint32_t, uint32_t>>& out) const {
    // Box i is tested against the boxes after it eight at a time, until one's lower bound on the
    // sweep axis passes its upper bound: the lanes before that box are the candidates, tested
    // as the scalar sweep would test them, and the hits are kept in sweep order.
    const uint32_t begin = stripBegin_[strip];
    const uint32_t end = stripBegin_[strip + 1];
    const SweptBoxes& s = sorted_;
    static_assert(kLanes == 8, "laneIndex and the full-row mask below count eight lanes");
    const LaneMask laneIndex = {0, 1, 2, 3, 4, 5, 6, 7};
    const bool limited = maxPairs_ != SIZE_MAX;
    for (uint32_t i = begin; i < end; ++i) {
        const size_t before = out.size();
        const Lanes aMax0 = Splat(s.max0[i]);
        const Lanes aMin1 = Splat(s.min1[i]);
        const Lanes aMax1 = Splat(s.max1[i]);
        const Lanes aMin2 = Splat(s.min2[i]);
        const Lanes aMax2 = Splat(s.max2[i]);
        const LaneMask aStatic = LaneMask{} + s.isStatic[i];
        for (uint32_t j = i + 1; j < end; j += kLanes) {
            const LaneMask inStrip = laneIndex < LaneMask{} + static_cast<int32_t>(end - j);
            const uint32_t ahead = LaneBits((LoadLanes(&s.min0[j]) <= aMax0) & inStrip);
            const uint32_t candidates = ahead & ~(ahead + 1);  // up to the first lane that is not
            if (candidates == 0) break;
            const LaneMask overlap =
                (aMin1 <= LoadLanes(&s.max1[j])) & (LoadLanes(&s.min1[j]) <= aMax1) &
                (aMin2 <= LoadLanes(&s.max2[j])) & (LoadLanes(&s.min2[j]) <= aMax2) &
                ~(aStatic & LoadMask(&s.isStatic[j]));
            for (uint32_t hits = LaneBits(overlap) & candidates; hits != 0; hits &= hits - 1) {
                const uint32_t b = j + static_cast<uint32_t>(__builtin_ctz(hits));
                if (strips.Of(std::max(s.min1[i], s.min1[b])) == strip) {
                    out.emplace_back(std::min(s.box[i], s.box[b]), std::max(s.box[i], s.box[b]));
                }
            }
            if (candidates != (1u << kLanes) - 1) break;
        }
        if (limited) {
            const size_t added = out.size() - before;
            if (found_.fetch_add(added, std::memory_order_relaxed) + added > maxPairs_) return;
        }
    }
}

void SweepAndPrune::DealIntoStrips(std::span<const BroadPhaseBox> boxes, const Strips& strips,
                                   int axis, int stripAxis, int other2) {
    // A counting sort by strip that keeps sweep order within each strip, in parallel over
    // chunks of the sweep order: each chunk counts its boxes per strip, the counts give every
    // chunk its place in every strip, and the chunks fill their places at once.
    const size_t n = order_.size();
    const size_t chunkSize =
        std::max<size_t>(kMinDealChunk, (n + kMaxDealChunks - 1) / kMaxDealChunks);
    const auto chunks = static_cast<uint32_t>((n + chunkSize - 1) / chunkSize);
    const uint32_t count = strips.count;
    chunkStripCount_.assign(size_t{chunks} * count, 0);
    const auto forChunk = [&](uint32_t chunk, auto&& visit) {
        const size_t end = std::min(n, (chunk + 1) * chunkSize);
        for (size_t i = chunk * chunkSize; i < end; ++i) {
            const BroadPhaseBox& box = boxes[order_[i].box];
            const uint32_t last = strips.Of(box.max[stripAxis]);
            for (uint32_t k = strips.Of(box.min[stripAxis]); k <= last; ++k) visit(k, i, box);
        }
    };
    ParallelFor(0, chunks, 1, [&](uint32_t chunk) {
        uint32_t* counts = chunkStripCount_.data() + size_t{chunk} * count;
        forChunk(chunk, [&](uint32_t k, size_t, const BroadPhaseBox&) { ++counts[k]; });
    });
    // Now each (chunk, strip)'s first place in sorted_, strip by strip, chunk by chunk.
    stripBegin_.assign(count + 1, 0);
    uint32_t place = 0;
    for (uint32_t k = 0; k < count; ++k) {
        stripBegin_[k] = place;
        for (uint32_t chunk = 0; chunk < chunks; ++chunk) {
            uint32_t& at = chunkStripCount_[size_t{chunk} * count + k];
            const uint32_t boxesHere = at;
            at = place;
            place += boxesHere;
        }
    }
    stripBegin_[count] = place;
    sorted_.Resize(place);
    ParallelFor(0, chunks, 1, [&](uint32_t chunk) {
        uint32_t* next = chunkStripCount_.data() + size_t{chunk} * count;
        forChunk(chunk, [&](uint32_t k, size_t i, const BroadPhaseBox& box) {
            const uint32_t at = next[k]++;
            sorted_.min0[at] = box.min[axis];
            sorted_.max0[at] = box.max[axis];
            sorted_.min1[at] = box.min[stripAxis];
            sorted_.max1[at] = box.max[stripAxis];
            sorted_.min2[at] = box.min[other2];
            sorted_.max2[at] = box.max[other2];
            sorted_.box[at] = order_[i].box;
            sorted_.isStatic[at] = box.isStatic ? -1 : 0;
        });
    });
}

SweepAndPrune::Strips SweepAndPrune::PlanStrips(std::span<const BroadPhaseBox> boxes, int stripAxis,
                                                float low, float high) {
    Strips one;
    const size_t n = boxes.size();
    // Strips twice as wide as the median box, so that most boxes lie in one or two; the median
    // of an even sample of at most kWidthSamples boxes is as good a guide.
    const size_t stride = (n + kWidthSamples - 1) / kWidthSamples;
    extents_.clear();
    for (size_t i = 0; i < n; i += stride) {
        const float extent = boxes[i].max[stripAxis] - boxes[i].min[stripAxis];
        extents_.push_back(std::isnan(extent) ? 0.0f : extent);  // nth_element needs an order
    }
    const size_t middle = extents_.size() / 2;
    std::nth_element(extents_.begin(), extents_.begin() + middle, extents_.end());
    const float width = 2.0f * extents_[middle];
    if (!(width > 0.0f) || !(high - low > width) || !std::isfinite(high - low)) return one;
    const double wanted = std::ceil(static_cast<double>(high - low) / width);
    const auto count = static_cast<uint32_t>(
        std::min<double>({wanted, double(kMaxStrips), double(n / kMinBoxesPerStrip)}));
    if (count <= 1) return one;
    Strips strips{count, low, static_cast<float>(count / static_cast<double>(high - low))};
    const size_t spans = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, 4096), size_t{0},
        [&](const tbb::blocked_range<size_t>& r, size_t sum) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                sum += strips.Of(boxes[i].max[stripAxis]) - strips.Of(boxes[i].min[stripAxis]) + 1;
            }
            return sum;
        },
        std::plus<size_t>());
    return spans <= kMaxStripsPerBox * n ? strips : one;
}

void SweepAndPrune::Ranks(std::vector<uint32_t>& rankOfBox) const {
    rankOfBox.resize(order_.size());
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, static_cast<uint32_t>(order_.size()), 4096),
                      [&](const tbb::blocked_range<uint32_t>& r) {
                          for (uint32_t rank = r.begin(); rank < r.end(); ++rank) {
                              rankOfBox[order_[rank].box] = rank;
                          }
                      });
}

void SweepAndPrune::Ranks(std::span<const uint32_t> to, std::span<uint32_t> out) const {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, static_cast<uint32_t>(order_.size()), 4096),
                      [&](const tbb::blocked_range<uint32_t>& r) {
                          for (uint32_t rank = r.begin(); rank < r.end(); ++rank) {
                              out[to[order_[rank].box]] = rank;
                          }
                      });
}

}  // namespace rtrt::physics
