#include "bench/accuracy/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rtrt {
namespace {

// |a - b| of the displayed (clamped) colours per channel; a channel that is not a number in
// either, which no display shows, is as far off as a channel can be (1): a NaN pixel had passed
// as a perfect match (its RMSE NaN, PSNR infinite, never an outlier).
vec3 Difference(vec3 a, vec3 b) {
    vec3 d;
    for (int c = 0; c < 3; ++c)
        d[c] = std::isnan(a[c]) || std::isnan(b[c])
                   ? 1.0f
                   : std::fabs(std::clamp(a[c], 0.0f, 1.0f) - std::clamp(b[c], 0.0f, 1.0f));
    return d;
}

void CheckSameSize(size_t a, size_t b) {
    if (a != b || a == 0) throw std::invalid_argument("image metrics: sizes differ or are empty");
}

void CheckSameSize(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument("image metrics: sizes differ");
    CheckSameSize(a.pixels.size(), b.pixels.size());
}

}  // namespace

double Rmse(const Image& image, const Image& reference) {
    CheckSameSize(image, reference);
    double sum = 0.0;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const vec3 d = Difference(image.pixels[i], reference.pixels[i]);
        sum += double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    }
    return std::sqrt(sum / (3.0 * double(image.pixels.size())));
}

double Psnr(double rmse) { return rmse > 0.0 ? -20.0 * std::log10(rmse) : HUGE_VAL; }

double OutlierRate(const Image& image, const Image& reference, float threshold) {
    CheckSameSize(image, reference);
    size_t outliers = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i)
        if (MaxComponent(Difference(image.pixels[i], reference.pixels[i])) > threshold) ++outliers;
    return double(outliers) / double(image.pixels.size());
}

double MismatchRate(const std::vector<uint32_t>& objects, const std::vector<uint32_t>& reference) {
    CheckSameSize(objects.size(), reference.size());
    size_t differ = 0;
    for (size_t i = 0; i < objects.size(); ++i) differ += objects[i] != reference[i];
    return double(differ) / double(objects.size());
}

Image DifferenceImage(const Image& image, const Image& reference) {
    CheckSameSize(image, reference);
    Image out(image.width, image.height);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        out.pixels[i] = Difference(image.pixels[i], reference.pixels[i]);
    return out;
}

}  // namespace rtrt
