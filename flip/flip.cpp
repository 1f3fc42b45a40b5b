#include "flip/flip.h"

#include "flip/color_spaces.h"

#include <fmt/format.h>
#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace kdop {
namespace {

using flip::Color;

using flip::kPc;
using flip::kPt;
using flip::kQc;
static_assert(flip::kQf == 0.5f, "the feature error's power is taken as a square root");

// One pass of a separable filter over a line of `width` pixels, its weights k[0..radius] for
// offsets 0..radius (flip_filters.h). `neighbors(j)` gives the lines at offsets -j and +j (the
// pixels beside in a padded row, or the clamped rows above and below), `center` the line itself.
//
// Written as sums of differences where the kernel says so: an antisymmetric kernel as
// k[j] (I[+j] - I[-j]), and the zero-sum point kernel (positive weights sum to 1, negative to -1)
// as k[j] ((I[-j] - I[0]) + (I[+j] - I[0])). That is the same sum as the reference's plain one,
// and it is exactly 0 where the image is flat, where the plain one leaves float rounding of about
// 1e-8 that the feature error's square root turns into 1e-4.
enum class Kernel { symmetric, antisymmetric, zero_sum };

template <Kernel kind>
float first_term(float k0, float center) {
    return kind == Kernel::symmetric ? k0 * center : 0.0f;
}

template <Kernel kind>
float tap(float kj, float minus, float center, float plus) {
    if constexpr (kind == Kernel::symmetric) return kj * (minus + plus);
    if constexpr (kind == Kernel::antisymmetric) return kj * (plus - minus);
    return kj * ((minus - center) + (plus - center));
}

// Two loop orders, each the faster one where it is used (callgrind, a 320x180 pair): along rows,
// tap by tap over the whole row, which the compiler vectorizes (under half the instructions of blocks
// there); along columns, blocks of 16 pixels summed in registers over every tap, then stored
// (0.6 times the instructions of tap by tap there).
template <Kernel kind, class Neighbors>
void filter_tap_by_tap(const float* center, Neighbors neighbors, int width, const std::vector<float>& k,
                       float* __restrict out) {
    for (int x = 0; x < width; ++x) out[x] = first_term<kind>(k[0], center[x]);
    for (int j = 1; j < int(k.size()); ++j) {
        const auto [minus, plus] = neighbors(j);
        const float kj = k[std::size_t(j)];
        for (int x = 0; x < width; ++x) out[x] += tap<kind>(kj, minus[x], center[x], plus[x]);
    }
}

template <Kernel kind, int count, class Neighbors>
void filter_block(const float* center, Neighbors neighbors, int x, const std::vector<float>& k, float* out) {
    float sum[count];
    for (int i = 0; i < count; ++i) sum[i] = first_term<kind>(k[0], center[x + i]);
    for (int j = 1; j < int(k.size()); ++j) {
        const auto [minus, plus] = neighbors(j);
        const float kj = k[std::size_t(j)];
        for (int i = 0; i < count; ++i) sum[i] += tap<kind>(kj, minus[x + i], center[x + i], plus[x + i]);
    }
    for (int i = 0; i < count; ++i) out[x + i] = sum[i];
}

template <Kernel kind, class Neighbors>
void filter_by_blocks(const float* center, Neighbors neighbors, int width, const std::vector<float>& k, float* out) {
    constexpr int block = 16;
    int x = 0;
    for (; x + block <= width; x += block) filter_block<kind, block>(center, neighbors, x, k, out);
    for (; x < width; ++x) filter_block<kind, 1>(center, neighbors, x, k, out);
}

// A row padded on both sides with copies of its end pixels (clamp-to-edge): `row` is pixel 0.
template <Kernel kind>
void filter_row(const float* row, int width, const std::vector<float>& k, float* out) {
    filter_tap_by_tap<kind>(
        row,
        [row](int j) {
            return std::pair{row - j, row + j};
        },
        width, k, out);
}

// Row y of a width x height plane, filtered vertically with rows clamped to the plane. The plane
// holds `ring` rows, row r in slot r % ring: the rows y - radius .. y + radius must be there.
template <Kernel kind>
void filter_column(const float* plane, int width, int height, int ring, int y, const std::vector<float>& k,
                   float* out) {
    auto row = [=](int r) { return plane + std::size_t(std::clamp(r, 0, height - 1) % ring) * std::size_t(width); };
    filter_by_blocks<kind>(
        row(y),
        [&](int j) {
            return std::pair{row(y - j), row(y + j)};
        },
        width, k, out);
}

// A CSF-filtered YCxCz color as the color metric sees it: clamped to [0, 1] in linear RGB (the
// filters can leave the gamut), then Hunt-adjusted L*a*b*.
Color<float> perceived(const Color<float>& filtered_ycxcz) {
    const Color<float> rgb = flip::xyz_to_linear_rgb(flip::ycxcz_to_xyz(filtered_ycxcz));
    return flip::hunt_adjust(flip::xyz_to_lab(flip::linear_rgb_to_xyz(glm::clamp(rgb, 0.0f, 1.0f))));
}

// The largest HyAB distance in Hunt-adjusted L*a*b* between two colors of the RGB cube, which the
// paper takes to be green's and blue's, raised to qc.
double green_blue_distance() {
    const auto adjusted = [](Color<double> rgb) {
        return flip::hunt_adjust(flip::xyz_to_lab(flip::linear_rgb_to_xyz(rgb)));
    };
    return std::pow(flip::hyab(adjusted({0, 1, 0}), adjusted({0, 0, 1})), double(kQc));
}

float length(float a, float b) { return std::sqrt(a * a + b * b); }

const char* const kChannelNames[3] = {"red", "green", "blue"};

} // namespace

double pixels_per_degree(const ViewingConditions& viewing) {
    return viewing.distance_m * (viewing.display_width_px / viewing.display_width_m) * (std::numbers::pi / 180.0);
}

Result<void> check_pixels_per_degree(double pixels_per_degree) {
    if (!(pixels_per_degree >= kMinPixelsPerDegree && pixels_per_degree <= kMaxPixelsPerDegree))
        return fail(fmt::format("pixels per degree must be a number from {} to {}, got {}", kMinPixelsPerDegree,
                                kMaxPixelsPerDegree, pixels_per_degree));
    return {};
}

Result<void> check_ldr_image(const Image& image, const std::string& what) {
    if (image.width == 0 || image.height == 0) return fail(fmt::format("{}: the image is empty", what));
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = image.at(x, y)[c];
                if (!(v >= 0.0f && v <= 1.0f)) // NaN fails too
                    return fail(fmt::format("{}: pixel ({}, {}) has {} = {}; LDR-FLIP takes linear RGB from 0 to 1 "
                                            "and clamps nothing (for other values, HDR-FLIP: kdop flip --hdr)",
                                            what, x, y, kChannelNames[c], v));
            }
    return {};
}

double mean_error(std::span<const float> error_map) {
    // The reference's C++ pooling sums in float; a double sum of 57,600 or 8 million values is the
    // same mean without float's rounding drift.
    double sum = 0;
    for (float e : error_map) sum += e;
    return error_map.empty() ? 0.0 : sum / double(error_map.size());
}

LdrFlip::LdrFlip(double pixels_per_degree) : ppd_(pixels_per_degree) {
    if (auto ok = check_pixels_per_degree(pixels_per_degree); !ok) throw std::invalid_argument(ok.error().message);
    csf_ = flip::make_csf_kernels(ppd_);
    features_ = flip::make_feature_kernels(ppd_);
    // The reference computes these in float; here in double, then rounded.
    const double cmax = green_blue_distance();
    cmax_ = float(cmax);
    pccmax_ = float(double(kPc) * cmax);
}

Result<double> LdrFlip::mean(const Image& reference, const Image& test) const {
    std::vector<float> error(reference.pixels.size());
    if (auto ok = evaluate(reference, test, error.data(), nullptr, nullptr); !ok) return std::unexpected(ok.error());
    return mean_error(error);
}

Result<std::vector<float>> LdrFlip::error_map(const Image& reference, const Image& test) const {
    std::vector<float> error(reference.pixels.size());
    if (auto ok = evaluate(reference, test, error.data(), nullptr, nullptr); !ok) return std::unexpected(ok.error());
    return error;
}

Result<FlipTerms> LdrFlip::terms(const Image& reference, const Image& test) const {
    FlipTerms t;
    t.color.resize(reference.pixels.size());
    t.feature.resize(reference.pixels.size());
    t.error.resize(reference.pixels.size());
    if (auto ok = evaluate(reference, test, t.error.data(), t.color.data(), t.feature.data()); !ok)
        return std::unexpected(ok.error());
    return t;
}

Result<void> LdrFlip::evaluate(const Image& reference, const Image& test, float* error, float* color,
                               float* feature) const {
    if (auto ok = check_ldr_image(reference, "reference image"); !ok) return ok;
    if (test.width != reference.width || test.height != reference.height)
        return fail(fmt::format("test image: {}x{}, but the reference image is {}x{}", test.width, test.height,
                                reference.width, reference.height));
    if (auto ok = check_ldr_image(test, "test image"); !ok) return ok;

    const int w = int(reference.width), h = int(reference.height);

    // Pass 1, along rows: each image to YCxCz and its achromatic channel, then every horizontal
    // pass of the separable filters. Pass 2, along columns, one output row at a time, then that
    // row's errors. Pass 1 runs ahead of pass 2 into a ring of the rows pass 2 still needs, not
    // whole planes: 2 x 7 planes of a 1920x1080 pair would be 116 MB, written once and read once.
    // The filters separate as in the reference: the CSF of each channel is g(x) g(y) (two such
    // terms for Cz), d/dx is edge(x) gaussian(y), d/dy is gaussian(x) edge(y), and likewise for
    // the second derivatives with `point`.
    enum { hY, hCx, hCz1, hCz2, hGaussian, hEdge, hPoint, kHorizontal };
    enum { vY, vCx, vCz1, vCz2, vDx, vDxx, vDy, vDyy, kVertical };
    const int pad = std::max(csf_.radius, features_.radius);
    const int ring = std::min(h, 2 * pad + 1);
    const std::size_t ring_plane = std::size_t(ring) * std::size_t(w);
    const std::size_t padded = std::size_t(w) + 2 * std::size_t(pad);
    auto horizontal = std::make_unique_for_overwrite<float[]>(2 * kHorizontal * ring_plane);
    auto lines = std::make_unique_for_overwrite<float[]>(4 * padded);
    auto vertical = std::make_unique_for_overwrite<float[]>(2 * kVertical * std::size_t(w));

    const Image* images[2] = {&reference, &test};
    float* const y_row = lines.get() + pad;
    float* const cx_row = y_row + padded;
    float* const cz_row = cx_row + padded;
    float* const achromatic_row = cz_row + padded;
    auto filter_rows = [&](int y) { // row y of both images' horizontal planes, into its slot
        for (int i = 0; i < 2; ++i) {
            float* planes = horizontal.get() + std::size_t(i) * kHorizontal * ring_plane;
            for (int x = 0; x < w; ++x) {
                const glm::vec4& p = images[i]->at(std::uint32_t(x), std::uint32_t(y));
                const Color<float> ycxcz = flip::xyz_to_ycxcz(flip::linear_rgb_to_xyz(Color<float>(p.r, p.g, p.b)));
                y_row[x] = ycxcz.x;
                cx_row[x] = ycxcz.y;
                cz_row[x] = ycxcz.z;
                // The features' input: Y of YCxCz normalized to [0, 1], as in the reference.
                achromatic_row[x] = (ycxcz.x + 16.0f) / 116.0f;
            }
            for (float* row : {y_row, cx_row, cz_row, achromatic_row}) {
                std::fill(row - pad, row, row[0]);
                std::fill(row + w, row + w + pad, row[w - 1]);
            }
            auto plane = [&](int k) {
                return planes + std::size_t(k) * ring_plane + std::size_t(y % ring) * std::size_t(w);
            };
            filter_row<Kernel::symmetric>(y_row, w, csf_.achromatic, plane(hY));
            filter_row<Kernel::symmetric>(cx_row, w, csf_.red_green, plane(hCx));
            filter_row<Kernel::symmetric>(cz_row, w, csf_.blue_yellow_1, plane(hCz1));
            filter_row<Kernel::symmetric>(cz_row, w, csf_.blue_yellow_2, plane(hCz2));
            filter_row<Kernel::symmetric>(achromatic_row, w, features_.gaussian, plane(hGaussian));
            filter_row<Kernel::antisymmetric>(achromatic_row, w, features_.edge, plane(hEdge));
            filter_row<Kernel::zero_sum>(achromatic_row, w, features_.point, plane(hPoint));
        }
    };

    const float inv_sqrt2 = float(1.0 / std::numbers::sqrt2);
    int rows_ready = 0; // rows of the horizontal planes filtered so far
    for (int y = 0; y < h; ++y) {
        // Row y + pad overwrites row y - pad - 1, which no output row from y on reads.
        for (; rows_ready <= std::min(y + pad, h - 1); ++rows_ready) filter_rows(rows_ready);
        for (int i = 0; i < 2; ++i) {
            const float* planes = horizontal.get() + std::size_t(i) * kHorizontal * ring_plane;
            float* rows = vertical.get() + std::size_t(i) * kVertical * std::size_t(w);
            auto plane = [&](int k) { return planes + std::size_t(k) * ring_plane; };
            auto row = [&](int k) { return rows + std::size_t(k) * std::size_t(w); };
            filter_column<Kernel::symmetric>(plane(hY), w, h, ring, y, csf_.achromatic, row(vY));
            filter_column<Kernel::symmetric>(plane(hCx), w, h, ring, y, csf_.red_green, row(vCx));
            filter_column<Kernel::symmetric>(plane(hCz1), w, h, ring, y, csf_.blue_yellow_1, row(vCz1));
            filter_column<Kernel::symmetric>(plane(hCz2), w, h, ring, y, csf_.blue_yellow_2, row(vCz2));
            filter_column<Kernel::symmetric>(plane(hEdge), w, h, ring, y, features_.gaussian, row(vDx));
            filter_column<Kernel::symmetric>(plane(hPoint), w, h, ring, y, features_.gaussian, row(vDxx));
            filter_column<Kernel::antisymmetric>(plane(hGaussian), w, h, ring, y, features_.edge, row(vDy));
            filter_column<Kernel::zero_sum>(plane(hGaussian), w, h, ring, y, features_.point, row(vDyy));
        }
        const float* r = vertical.get();
        const float* t = r + kVertical * std::size_t(w);
        auto at = [w](const float* rows, int k, int x) {
            return rows[std::size_t(k) * std::size_t(w) + std::size_t(x)];
        };
        for (int x = 0; x < w; ++x) {
            auto filtered = [&](const float* rows) {
                return Color<float>(at(rows, vY, x), at(rows, vCx, x), at(rows, vCz1, x) + at(rows, vCz2, x));
            };
            const float distance = std::pow(flip::hyab(perceived(filtered(r)), perceived(filtered(t))), kQc);
            const float color_error = distance < pccmax_
                                          ? distance * (kPt / pccmax_)
                                          : kPt + ((distance - pccmax_) / (cmax_ - pccmax_)) * (1.0f - kPt);

            auto edge = [&](const float* rows) { return length(at(rows, vDx, x), at(rows, vDy, x)); };
            auto point = [&](const float* rows) { return length(at(rows, vDxx, x), at(rows, vDyy, x)); };
            const float feature_error =
                std::sqrt(inv_sqrt2 * std::max(std::abs(edge(r) - edge(t)), std::abs(point(r) - point(t))));

            const std::size_t index = std::size_t(y) * std::size_t(w) + std::size_t(x);
            error[index] = std::pow(color_error, 1.0f - feature_error);
            if (color) color[index] = color_error;
            if (feature) feature[index] = feature_error;
        }
    }
    return {};
}

} // namespace kdop
