#include "engine/render_rt/view_finish.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rtrt {
namespace {

// Blue -> cyan -> green -> yellow -> red: a perceptually ordered scale for counts.
vec3 HeatColour(float t) {
    static const vec3 kStops[] = {{0.05f, 0.05f, 0.35f},
                                  {0.0f, 0.55f, 0.9f},
                                  {0.1f, 0.8f, 0.2f},
                                  {0.95f, 0.9f, 0.1f},
                                  {0.9f, 0.1f, 0.05f}};
    t = (t > 0.0f ? std::min(t, 1.0f) : 0.0f) * 4.0f;  // NaN too is 0: it indexes the stops
    const int i = std::min(int(t), 3);
    return glm::mix(kStops[i], kStops[i + 1], t - float(i));
}

// 3x5 pixel digits, one row per 3 bits (most significant bit = left column).
constexpr uint8_t kDigits[10][5] = {
    {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};

void DrawNumber(Image& image, uint32_t value, int x, int y, int scale, vec3 colour) {
    const std::string text = std::to_string(value);
    for (char c : text) {
        const uint8_t* glyph = kDigits[c - '0'];
        for (int row = 0; row < 5; ++row)
            for (int col = 0; col < 3; ++col) {
                if (!(glyph[row] & (4 >> col))) continue;
                for (int dy = 0; dy < scale; ++dy)
                    for (int dx = 0; dx < scale; ++dx) {
                        const int px = x + col * scale + dx, py = y + row * scale + dy;
                        if (px >= 0 && py >= 0 && px < int(image.width) && py < int(image.height))
                            image.At(px, py) = colour;
                    }
            }
        x += 4 * scale;
    }
}

// The colour bar along the bottom with 0, half and the maximum written under it.
void DrawLegend(Image& image, float maxSteps) {
    const int scale = std::max(1, int(image.height) / 240);
    const int barHeight = 4 * scale, labelHeight = 7 * scale;
    const int top = int(image.height) - barHeight - labelHeight;
    if (top < 0) return;
    for (int y = top; y < int(image.height); ++y)
        for (uint32_t x = 0; x < image.width; ++x)
            image.At(x, y) =
                y < top + barHeight
                    ? HeatColour(image.width > 1 ? float(x) / float(image.width - 1) : 0.0f)
                    : vec3(0.0f);
    const vec3 white(1.0f);
    const int labelY = top + barHeight + scale;
    const uint32_t maxLabel = uint32_t(maxSteps);
    DrawNumber(image, 0, scale, labelY, scale, white);
    const int halfWidth = int(std::to_string(maxLabel / 2).size()) * 4 * scale;
    DrawNumber(image, maxLabel / 2, int(image.width) / 2 - halfWidth / 2, labelY, scale, white);
    const int maxWidth = int(std::to_string(maxLabel).size()) * 4 * scale;
    DrawNumber(image, maxLabel, int(image.width) - maxWidth - scale, labelY, scale, white);
}

}  // namespace

Image FinishView(const Image& raw, ViewMode view, HeatmapScale* heatmap) {
    Image out = raw;
    switch (view) {
        case ViewMode::kShaded:
            return out;
        case ViewMode::kNormals:
            for (vec3& p : out.pixels) p = (p == vec3(0.0f)) ? vec3(0.0f) : 0.5f * p + vec3(0.5f);
            return out;
        case ViewMode::kDepth: {
            float nearest = kInfinity, farthest = 0.0f;
            for (const vec3& p : raw.pixels)
                if (std::isfinite(p.x)) {
                    nearest = std::min(nearest, p.x);
                    farthest = std::max(farthest, p.x);
                }
            const float range = std::max(farthest - nearest, 1e-20f);
            for (vec3& p : out.pixels)
                p = std::isfinite(p.x) ? vec3(1.0f - 0.85f * (p.x - nearest) / range) : vec3(0.0f);
            return out;
        }
        case ViewMode::kHeatmap: {
            // The top of the scale is the 99.5th percentile, so a few extreme pixels do not
            // wash out the rest; pixels above it take the top colour.
            std::vector<float> steps(raw.pixels.size());
            for (size_t i = 0; i < steps.size(); ++i) steps[i] = raw.pixels[i].x + raw.pixels[i].y;
            auto top = steps.begin() + std::ptrdiff_t(0.995 * double(steps.size() - 1));
            std::nth_element(steps.begin(), top, steps.end());
            const float maxSteps = std::max(1.0f, std::ceil(*top));
            for (size_t i = 0; i < out.pixels.size(); ++i)
                out.pixels[i] = HeatColour((raw.pixels[i].x + raw.pixels[i].y) / maxSteps);
            DrawLegend(out, maxSteps);
            if (heatmap) heatmap->maxSteps = maxSteps;
            return out;
        }
    }
    return out;
}

}  // namespace rtrt
