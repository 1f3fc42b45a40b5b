// The color spaces of LDR-FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating
// Images", HPG 2020, section 3), as its reference implementation (NVlabs/flip) defines them: sRGB's
// transfer function, linear sRGB <-> CIE XYZ under D65, XYZ <-> YCxCz (the opponent space the
// contrast sensitivity filters work in), XYZ -> CIE L*a*b*, the Hunt adjustment and the HyAB
// distance. Each function is a template on the scalar, so the per-pixel path runs them in float
// (as the reference does) and the constants and tests in double.
//
// Contract: pure functions of their arguments, no range checks (LdrFlip checks its inputs); XYZ is
// absolute (white is kD65White), L*a*b* and YCxCz are relative to kD65White.
#pragma once

#include "images/srgb.h"

#include <glm/vec3.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

namespace kdop::flip {

template <class T>
using Color = glm::vec<3, T, glm::defaultp>;

using Matrix3 = std::array<std::array<double, 3>, 3>; // rows

// Linear sRGB to XYZ as exact ratios (the reference cites image-engineering.de's technote 958,
// "How to convert between sRGB and CIEXYZ"); its rows sum to the white point below.
inline constexpr Matrix3 kLinearRgbToXyz{{
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0},
}};

constexpr Matrix3 inverse(const Matrix3& m) {
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1], c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2],
                 c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    return {{
        {c00 / det, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det, (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det},
        {c01 / det, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det, (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det},
        {c02 / det, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det, (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det},
    }};
}

// The reference writes this inverse out to nine digits ("found by taking the inverse"); computed
// here from the same ratios.
inline constexpr Matrix3 kXyzToLinearRgb = inverse(kLinearRgbToXyz);

// D65 as the XYZ of linear RGB white (1, 1, 1): the rows' sums, 0.950428545..., 1, 1.088900371...
// (the reference's DEFAULT_ILLUMINANT to nine digits), so white maps to L* = 100, a* = b* = 0.
inline constexpr std::array<double, 3> kD65White{
    kLinearRgbToXyz[0][0] + kLinearRgbToXyz[0][1] + kLinearRgbToXyz[0][2],
    kLinearRgbToXyz[1][0] + kLinearRgbToXyz[1][1] + kLinearRgbToXyz[1][2],
    kLinearRgbToXyz[2][0] + kLinearRgbToXyz[2][1] + kLinearRgbToXyz[2][2],
};

template <class T>
Color<T> multiply(const Matrix3& m, const Color<T>& v) {
    return {T(m[0][0]) * v.x + T(m[0][1]) * v.y + T(m[0][2]) * v.z,
            T(m[1][0]) * v.x + T(m[1][1]) * v.y + T(m[1][2]) * v.z,
            T(m[2][0]) * v.x + T(m[2][1]) * v.y + T(m[2][2]) * v.z};
}

// sRGB's transfer function, per channel, with the reference's thresholds (images/srgb.h).
using kdop::linear_to_srgb;
using kdop::srgb_to_linear;

template <class T>
Color<T> linear_rgb_to_xyz(const Color<T>& rgb) {
    return multiply(kLinearRgbToXyz, rgb);
}
template <class T>
Color<T> xyz_to_linear_rgb(const Color<T>& xyz) {
    return multiply(kXyzToLinearRgb, xyz);
}

// YCxCz (Kolpatzik and Bouman 1992; the paper's opponent space): L*a*b* without the cube root,
// linear in XYZ, so filtering it is filtering light.
template <class T>
Color<T> xyz_to_ycxcz(const Color<T>& xyz) {
    const T x = xyz.x / T(kD65White[0]), y = xyz.y / T(kD65White[1]), z = xyz.z / T(kD65White[2]);
    return {T(116) * y - T(16), T(500) * (x - y), T(200) * (y - z)};
}
template <class T>
Color<T> ycxcz_to_xyz(const Color<T>& ycxcz) {
    const T y = (ycxcz.x + T(16)) / T(116);
    return {(y + ycxcz.y / T(500)) * T(kD65White[0]), y * T(kD65White[1]), (y - ycxcz.z / T(200)) * T(kD65White[2])};
}

// The cube root of t > 0. In float, as LdrFlip's per-pixel path takes it six times a pixel: a first
// guess from the bits (the exponent divided by 3, within 3.5%) and two Halley steps, within 2.4e-7
// of the exact root from 0.008 to 1. The reference takes powf(t, 1/3) (within 1.0e-7); this is the
// same root to float precision and took 6% off a 320x180 pair here.
template <class T>
T cube_root(T t) {
    if constexpr (std::is_same_v<T, float>) {
        float y = std::bit_cast<float>(std::bit_cast<std::uint32_t>(t) / 3u + 709921077u);
        for (int i = 0; i < 2; ++i) {
            const float y3 = y * y * y;
            y = y * (y3 + 2.0f * t) / (2.0f * y3 + t);
        }
        return y;
    } else {
        return std::cbrt(t);
    }
}

// CIE 1976 L*a*b* relative to D65.
template <class T>
T lab_f(T t) {
    constexpr T delta = T(6) / T(29);
    return t > delta * delta * delta ? cube_root(t) : t / (T(3) * delta * delta) + T(4) / T(29);
}
template <class T>
Color<T> xyz_to_lab(const Color<T>& xyz) {
    const T fx = lab_f(xyz.x / T(kD65White[0])), fy = lab_f(xyz.y / T(kD65White[1])),
            fz = lab_f(xyz.z / T(kD65White[2]));
    return {T(116) * fy - T(16), T(500) * (fx - fy), T(200) * (fy - fz)};
}

// The Hunt effect (colorfulness grows with luminance), as the paper models it: a* and b* scaled
// by 0.01 L*.
template <class T>
Color<T> hunt_adjust(const Color<T>& lab) {
    return {lab.x, T(0.01) * lab.x * lab.y, T(0.01) * lab.x * lab.z};
}

// HyAB (Abasi et al. 2020): city-block distance in lightness plus Euclidean distance in a, b.
template <class T>
T hyab(const Color<T>& a, const Color<T>& b) {
    const T da = a.y - b.y, db = a.z - b.z;
    return std::abs(a.x - b.x) + std::sqrt(da * da + db * db);
}

} // namespace kdop::flip
