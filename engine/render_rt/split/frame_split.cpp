#include "engine/render_rt/split/frame_split.h"

#include <algorithm>
#include <cmath>

namespace rtrt {

FrameSplit::FrameSplit(uint32_t parts) : share_(std::max(1u, parts), 1.0 / std::max(1u, parts)) {}

std::vector<RowBand> FrameSplit::Bands(uint32_t height) const {
    const uint32_t parts = Parts();
    const uint32_t granules = (height + kRowGranule - 1) / kRowGranule;
    // Each part's whole granules by its share (largest remainders get the ones left over, the
    // earlier part on a tie), at least one each while there are enough.
    std::vector<uint32_t> count(parts, 0);
    const uint32_t floor = granules >= parts ? 1u : 0u;
    const uint32_t spare = granules - floor * parts;
    std::vector<double> remainder(parts);
    uint32_t given = 0;
    for (uint32_t p = 0; p < parts; ++p) {
        const double exact = share_[p] * spare;
        count[p] = floor + uint32_t(exact);
        remainder[p] = exact - std::floor(exact);
        given += count[p];
    }
    std::vector<uint32_t> order(parts);
    for (uint32_t p = 0; p < parts; ++p) order[p] = p;
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return remainder[a] > remainder[b]; });
    for (uint32_t k = 0; given < granules; k = (k + 1) % parts, ++given) ++count[order[k]];
    std::vector<RowBand> bands(parts);
    uint32_t row = 0;
    for (uint32_t p = 0; p < parts; ++p) {
        bands[p].begin = row;
        row = std::min(height, row + count[p] * kRowGranule);
        bands[p].end = row;
    }
    return bands;
}

void FrameSplit::Report(std::span<const RowBand> bands, std::span<const double> milliseconds) {
    if (milliseconds.size() != share_.size() || bands.size() != share_.size()) return;
    std::vector<double> speed(share_.size());
    double total = 0.0;
    for (size_t p = 0; p < share_.size(); ++p) {
        if (!(milliseconds[p] > 0.0) || bands[p].Rows() == 0) return;
        speed[p] = bands[p].Rows() / milliseconds[p];
        total += speed[p];
    }
    for (size_t p = 0; p < share_.size(); ++p) share_[p] = 0.5 * share_[p] + 0.5 * speed[p] / total;
}

}  // namespace rtrt
