#include "flip.h"
#include <cmath>
namespace kdop {
double pixels_per_degree(const ViewingConditions& v) { return v.distance_m * (v.display_width_px / v.display_width_m) * 3.14159265358979 / 180; }
Result<double> LdrFlip::mean(const Image& a, const Image& b) const {
    double s = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) s += std::abs(a.pixels[i].r - b.pixels[i].r) + std::abs(a.pixels[i].g - b.pixels[i].g) + std::abs(a.pixels[i].b - b.pixels[i].b);
    return s / a.pixels.size() / 3;
}
}
