#include "engine/render_rt/shading/texture_mips.h"

#include <algorithm>
#include <cmath>

#include "engine/render_rt/srgb.h"

namespace rtrt {
namespace {

// One channel's byte to the value that is averaged, and back.
float Decode(uint32_t byte, bool srgb) {
    const float v = float(byte) * (1.0f / 255.0f);
    return srgb ? SrgbDecode(v) : v;
}

uint32_t Encode(float v, bool srgb) {
    if (srgb) v = SrgbEncode(v);
    return uint32_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

std::vector<uint32_t> BuildMipChain(const uint32_t* rgba, uint32_t width, uint32_t height,
                                    uint32_t levels, bool srgb) {
    std::vector<uint32_t> out(rgba, rgba + size_t(width) * height);
    size_t above = 0;  // where the level above starts in out
    for (uint32_t level = 1; level < levels; ++level) {
        const uint32_t w = std::max(width / 2, 1u), h = std::max(height / 2, 1u);
        std::vector<uint32_t> next(size_t(w) * h);
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                // The texels of the level above that this one covers: 2x2, 3 wide or high where
                // an odd size leaves a last row or column over.
                const uint32_t x0 = 2 * x, y0 = 2 * y;
                const uint32_t x1 = std::min(x == w - 1 ? width : x0 + 2, width);
                const uint32_t y1 = std::min(y == h - 1 ? height : y0 + 2, height);
                float sum[4] = {0, 0, 0, 0};
                for (uint32_t j = y0; j < std::max(y1, y0 + 1); ++j)
                    for (uint32_t i = x0; i < std::max(x1, x0 + 1); ++i) {
                        const uint32_t t = out[above + size_t(j) * width + i];
                        for (int c = 0; c < 4; ++c)
                            sum[c] += Decode((t >> (8 * c)) & 0xffu, srgb && c < 3);
                    }
                const float n = float((std::max(x1, x0 + 1) - x0) * (std::max(y1, y0 + 1) - y0));
                uint32_t texel = 0;
                for (int c = 0; c < 4; ++c) texel |= Encode(sum[c] / n, srgb && c < 3) << (8 * c);
                next[size_t(y) * w + x] = texel;
            }
        above = out.size();
        out.insert(out.end(), next.begin(), next.end());
        width = w;
        height = h;
    }
    return out;
}

}  // namespace rtrt
