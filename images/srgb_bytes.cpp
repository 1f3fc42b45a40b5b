#include "images/srgb_bytes.h"

#include "images/srgb.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <bit>

namespace kdop {

std::uint8_t unit_byte_by_formula(float value) {
    std::uint8_t byte = 0;
    OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, &value, OIIO::TypeDesc::UINT8, &byte, 1);
    return byte;
}

std::uint8_t srgb_byte_by_formula(float linear) { return unit_byte_by_formula(linear_to_srgb(linear)); }

ByteSteps::ByteSteps(std::uint8_t (*formula)(float)) {
    // Non-negative floats order as their bits do, so the bisection runs over the bits of [0, 1].
    for (int code = 1; code <= 255; ++code) {
        std::uint32_t low = 0, high = std::bit_cast<std::uint32_t>(1.0f);
        while (low < high) {
            const std::uint32_t middle = low + (high - low) / 2;
            if (formula(std::bit_cast<float>(middle)) >= code)
                high = middle;
            else
                low = middle + 1;
        }
        steps_[std::size_t(code - 1)] = std::bit_cast<float>(low);
    }
    const std::uint32_t buckets = (std::bit_cast<std::uint32_t>(1.0f) >> kBucketBits) + 1;
    for (std::uint32_t b = 0; b < buckets; ++b) {
        const float start = std::bit_cast<float>(b << kBucketBits);
        first_.push_back(std::uint8_t(std::upper_bound(steps_.begin(), steps_.end(), start) - steps_.begin()));
    }
}

const ByteSteps& ByteSteps::srgb() {
    static const ByteSteps steps(srgb_byte_by_formula);
    return steps;
}

const ByteSteps& ByteSteps::unit() {
    static const ByteSteps steps(unit_byte_by_formula);
    return steps;
}

} // namespace kdop
