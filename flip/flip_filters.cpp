#include "flip/flip_filters.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kdop::flip {
namespace {

using std::numbers::pi;

// The paper's spatial-domain Gaussian a sqrt(pi/b) exp(-pi^2 x^2 / b), x in degrees.
double csf_gaussian(double x, double a, double b) { return a * std::sqrt(pi / b) * std::exp(-pi * pi * x * x / b); }

// Weights for offsets -radius..radius, index j + radius.
std::vector<double> sample(int radius, auto weight) {
    std::vector<double> w(std::size_t(2 * radius + 1));
    for (int j = -radius; j <= radius; ++j) w[std::size_t(j + radius)] = weight(j);
    return w;
}

// Offsets 0..radius of a full kernel, each divided by `scale`.
std::vector<float> half(const std::vector<double>& full, int radius, double scale) {
    std::vector<float> h(std::size_t(radius + 1));
    for (int j = 0; j <= radius; ++j) h[std::size_t(j)] = float(full[std::size_t(j + radius)] / scale);
    return h;
}

double sum(const std::vector<double>& w) {
    double s = 0;
    for (double v : w) s += v;
    return s;
}

// Positive weights divided by their sum, negative ones by the magnitude of theirs.
std::vector<float> half_normalized_by_sign(const std::vector<double>& full, int radius) {
    double positive = 0, negative = 0;
    for (double v : full) (v > 0 ? positive : negative) += std::abs(v);
    std::vector<float> h(std::size_t(radius + 1));
    for (int j = 0; j <= radius; ++j) {
        const double v = full[std::size_t(j + radius)];
        h[std::size_t(j)] = float(v > 0 ? v / positive : v < 0 ? v / negative : 0.0);
    }
    return h;
}

} // namespace

int csf_radius(double pixels_per_degree) {
    const double widest = std::max(
        {kCsfAchromatic.b1, kCsfAchromatic.b2, kCsfRedGreen.b1, kCsfRedGreen.b2, kCsfBlueYellow.b1, kCsfBlueYellow.b2});
    return int(std::ceil(3.0 * std::sqrt(widest / (2.0 * pi * pi)) * pixels_per_degree));
}

int feature_radius(double pixels_per_degree) {
    return int(std::ceil(3.0 * 0.5 * kFeatureWidthDegrees * pixels_per_degree));
}

CsfKernels make_csf_kernels(double pixels_per_degree) {
    static_assert(kCsfAchromatic.a2 == 0 && kCsfRedGreen.a2 == 0, "Y and Cx are single Gaussians, separated as such");
    CsfKernels k;
    k.radius = csf_radius(pixels_per_degree);
    const double dx = 1.0 / pixels_per_degree; // degrees per pixel
    auto gaussian = [&](const CsfGaussians& c) {
        return sample(k.radius, [&](int j) { return csf_gaussian(j * dx, c.a1, c.b1); });
    };
    const std::vector<double> y = gaussian(kCsfAchromatic), cx = gaussian(kCsfRedGreen);
    // g1(x) g1(y) + g2(x) g2(y) with g = sqrt(a sqrt(pi/b)) exp(-pi^2 x^2/b) is the paper's 2-D sum at
    // r^2 = x^2 + y^2; over the square it sums to S1^2 + S2^2, so each pass divides by its root.
    auto root = [&](double a, double b) {
        return sample(k.radius, [&](int j) {
            return std::sqrt(a * std::sqrt(pi / b)) * std::exp(-pi * pi * (j * dx) * (j * dx) / b);
        });
    };
    const std::vector<double> cz1 = root(kCsfBlueYellow.a1, kCsfBlueYellow.b1),
                              cz2 = root(kCsfBlueYellow.a2, kCsfBlueYellow.b2);
    const double cz_scale = std::sqrt(sum(cz1) * sum(cz1) + sum(cz2) * sum(cz2));
    k.achromatic = half(y, k.radius, sum(y));
    k.red_green = half(cx, k.radius, sum(cx));
    k.blue_yellow_1 = half(cz1, k.radius, cz_scale);
    k.blue_yellow_2 = half(cz2, k.radius, cz_scale);
    return k;
}

FeatureKernels make_feature_kernels(double pixels_per_degree) {
    FeatureKernels k;
    k.radius = feature_radius(pixels_per_degree);
    k.sigma = 0.5 * kFeatureWidthDegrees * pixels_per_degree;
    const double s2 = k.sigma * k.sigma;
    auto g = [&](int j) { return std::exp(-double(j) * j / (2.0 * s2)); };
    const std::vector<double> gaussian = sample(k.radius, g);
    k.gaussian = half(gaussian, k.radius, sum(gaussian));
    k.edge = half_normalized_by_sign(sample(k.radius, [&](int j) { return -double(j) * g(j); }), k.radius);
    k.point =
        half_normalized_by_sign(sample(k.radius, [&](int j) { return (double(j) * j / s2 - 1.0) * g(j); }), k.radius);
    return k;
}

} // namespace kdop::flip
