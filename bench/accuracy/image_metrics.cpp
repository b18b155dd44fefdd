#include "bench/accuracy/image_metrics.h"

#include <cmath>
#include <stdexcept>

namespace rtrt {
namespace {

vec3 Clamped(vec3 c) { return glm::clamp(c, vec3(0.0f), vec3(1.0f)); }

void CheckSameSize(size_t a, size_t b) {
    if (a != b || a == 0) throw std::invalid_argument("image metrics: sizes differ or are empty");
}

}  // namespace

double Rmse(const Image& image, const Image& reference) {
    CheckSameSize(image.pixels.size(), reference.pixels.size());
    double sum = 0.0;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const vec3 d = Clamped(image.pixels[i]) - Clamped(reference.pixels[i]);
        sum += double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    }
    return std::sqrt(sum / (3.0 * double(image.pixels.size())));
}

double Psnr(double rmse) { return rmse > 0.0 ? -20.0 * std::log10(rmse) : HUGE_VAL; }

double OutlierRate(const Image& image, const Image& reference, float threshold) {
    CheckSameSize(image.pixels.size(), reference.pixels.size());
    size_t outliers = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const vec3 d = glm::abs(Clamped(image.pixels[i]) - Clamped(reference.pixels[i]));
        if (MaxComponent(d) > threshold) ++outliers;
    }
    return double(outliers) / double(image.pixels.size());
}

double MismatchRate(const std::vector<uint32_t>& objects, const std::vector<uint32_t>& reference) {
    CheckSameSize(objects.size(), reference.size());
    size_t differ = 0;
    for (size_t i = 0; i < objects.size(); ++i) differ += objects[i] != reference[i];
    return double(differ) / double(objects.size());
}

Image DifferenceImage(const Image& image, const Image& reference) {
    CheckSameSize(image.pixels.size(), reference.pixels.size());
    Image out(image.width, image.height);
    for (size_t i = 0; i < image.pixels.size(); ++i)
        out.pixels[i] = glm::abs(Clamped(image.pixels[i]) - Clamped(reference.pixels[i]));
    return out;
}

}  // namespace rtrt
