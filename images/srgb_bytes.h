// 8-bit sRGB codes of linear values in [0, 1], fast and exactly as before: each code is what
// linear_to_srgb (images/srgb.h) followed by OpenImageIO's float-to-8-bit conversion gives, found
// from the 255 linear values where the code steps up instead of a powf and a conversion per
// channel. The steps are found once, by bisection over the floats of that same composition. A
// table by the float's top bits (2^15 floats a bucket, 0.4% of the value: narrower than the
// steps' spacing) gives the code where a bucket starts, and one comparison with the next step
// finishes it. tests/image_io_test.cpp checks every float around each step and a sample of all the
// others. Writing report.html's viewer frames (hundreds of PNGs) spent a third of its time in the
// powf.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace kdop {

// The composition itself: what the steps are found from.
std::uint8_t srgb_byte_by_formula(float linear);
// The same for a value stored as it is (alpha): OpenImageIO's conversion alone.
std::uint8_t unit_byte_by_formula(float value);

class ByteSteps {
public:
    // The steps of the sRGB encoding, and those of the plain conversion; made on first use.
    static const ByteSteps& srgb();
    static const ByteSteps& unit();

    // The code of `value`, which must lie in [0, 1] (not NaN).
    std::uint8_t code(float value) const {
        std::uint32_t c = first_[std::bit_cast<std::uint32_t>(value) >> kBucketBits];
        while (c < 255 && value >= steps_[c]) ++c; // steps_[c] is where code c + 1 starts
        return std::uint8_t(c);
    }
    // The least float that gets code `code` (1 to 255).
    float step(int code) const { return steps_[std::size_t(code - 1)]; }

private:
    explicit ByteSteps(std::uint8_t (*formula)(float));
    static constexpr int kBucketBits = 15;
    std::array<float, 255> steps_{};
    std::vector<std::uint8_t> first_; // by bucket: the code of its first float
};

} // namespace kdop
