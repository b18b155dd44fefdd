#pragma once
// How far an image is from the reference (docs/accuracy.md defines each measure). Colours are
// clamped to [0, 1], as displayed, before they are compared; a channel that is NaN in either
// image differs by 1, the most a displayed channel can. Images of different sizes are refused.
#include <vector>

#include "engine/render_rt/image.h"

namespace rtrt {

// Root mean square error over every channel of every pixel.
double Rmse(const Image& image, const Image& reference);
// Peak signal-to-noise ratio for peak 1: 20 log10(1 / rmse) dB; infinity for identical images.
double Psnr(double rmse);
// Fraction of pixels with some channel more than threshold from the reference: acne, leaks and
// missed or extra objects, as opposed to the small differences of rounding.
double OutlierRate(const Image& image, const Image& reference, float threshold);
// Fraction of pixels whose primary hit object differs (a miss counts as object 0).
double MismatchRate(const std::vector<uint32_t>& objects, const std::vector<uint32_t>& reference);
// |image - reference| per pixel (clamped colours), for the report's pictures.
Image DifferenceImage(const Image& image, const Image& reference);

}  // namespace rtrt
