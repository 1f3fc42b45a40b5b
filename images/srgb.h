// sRGB's transfer function (IEC 61966-2-1), per channel, with the thresholds NVlabs/flip uses: how
// 8-bit files are decoded to kdop's linear values and encoded back (images/image_io.h), and the
// first step of FLIP (flip/color_spaces.h).
#pragma once

#include <cmath>

namespace kdop {

template <class T>
T srgb_to_linear(T encoded) {
    return encoded <= T(0.04045) ? encoded / T(12.92) : std::pow((encoded + T(0.055)) / T(1.055), T(2.4));
}

template <class T>
T linear_to_srgb(T linear) {
    return linear <= T(0.0031308) ? linear * T(12.92) : T(1.055) * std::pow(linear, T(1) / T(2.4)) - T(0.055);
}

} // namespace kdop
