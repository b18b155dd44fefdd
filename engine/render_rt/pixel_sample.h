#pragma once
// Where the samples of a pixel lie: n x n strata, one jittered point in each (stratified
// sampling, pbrt-v4 StratifiedSampler), the jitter a hash of pixel and sample index so that
// every run, on either back end, traces the same rays. One sample is the pixel centre.
#include "engine/core/math.h"

namespace rtrt {

// PCG hash: Jarzynski, Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3).
RT_HD inline uint32_t PcgHash(uint32_t v) {
    const uint32_t state = v * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Strata per side for a sample count: the largest n with n * n <= samples (at least 1).
RT_HD inline uint32_t StrataPerSide(uint32_t samples) {
    uint32_t n = 1;
    while ((n + 1) * (n + 1) <= samples) ++n;
    return n;
}

// Sample s (0 <= s < n * n) of pixel (x, y) as an offset in [0, 1)^2 from its top left corner.
RT_HD inline vec2 PixelSample(uint32_t x, uint32_t y, uint32_t s, uint32_t n) {
    if (n <= 1) return vec2(0.5f);
    const uint32_t h = PcgHash(PcgHash(PcgHash(x) ^ y) + s);
    // 16 bits per axis: exact in float, so the double reference sees the same positions.
    const float jx = float(h & 0xffffu) * (1.0f / 65536.0f);
    const float jy = float(h >> 16) * (1.0f / 65536.0f);
    return vec2((float(s % n) + jx) / float(n), (float(s / n) + jy) / float(n));
}

}  // namespace rtrt
