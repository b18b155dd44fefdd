#pragma once
// A frame's rows shared among several tracers (streams of one GPU, or GPUs), adapted frame to
// frame to how fast each traced its last share, so that they finish together and none waits.
// Pixels do not depend on which tracer computes them, so the image is the same for any split.
#include <cstdint>
#include <span>
#include <vector>

namespace rtrt {

struct RowBand {
    uint32_t begin = 0, end = 0;  // rows [begin, end)
    uint32_t Rows() const { return end - begin; }
};

class FrameSplit {
  public:
    // Bands are whole multiples of this many rows (the trace kernel's block height), but for the
    // last one, which ends at the frame's last row.
    static constexpr uint32_t kRowGranule = 8;

    explicit FrameSplit(uint32_t parts);

    uint32_t Parts() const { return uint32_t(share_.size()); }
    // The bands of a frame `height` rows high, in order from the top, one per part: equal shares
    // at first, then the shares Report last set. Every part gets at least one granule while the
    // frame has that many.
    std::vector<RowBand> Bands(uint32_t height) const;
    // How long each part took to trace its band of `bands` (a frame as Bands cut it, perhaps
    // before other reports moved the shares): the next
    // shares move halfway from the current ones to those proportional to each part's speed
    // (rows per millisecond), which settles within a few frames without chasing noise. A time
    // that is not positive (a band too small to measure) leaves the shares as they are.
    void Report(std::span<const RowBand> bands, std::span<const double> milliseconds);
    // The fraction of the rows each part is given.
    std::span<const double> Shares() const { return share_; }

  private:
    std::vector<double> share_;
};

}  // namespace rtrt
