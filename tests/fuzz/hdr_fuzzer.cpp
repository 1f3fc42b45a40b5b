// libFuzzer target: any bytes as two small HDR images' raw float values (any bit pattern: NaN,
// infinities, denormals, 1e38), a color map's exponent and an exposure, through the paths a
// renderer's HDR frames take: the color map the resolve clips in (core/color_map.h) and HDR-FLIP's
// exposure range and tone curves (flip/hdr_flip.h). Whatever check_mappable accepts must map to
// finite values, and a refusal must name a pixel; whatever HDR-FLIP accepts must give a finite mean
// and error map in [0, 1], and a refusal must be a message; the tone curves must be finite for any
// finite color and exposure float can scale by. Any violation aborts, which libFuzzer reports.
#include "core/color_map.h"
#include "flip/hdr_flip.h"
#include "tests/fuzz/fuzz_checks.h"

#include <fmt/format.h>
#include <glm/common.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

namespace {

using kdop::fuzz::require;

constexpr std::uint32_t kWidth = 4, kHeight = 3;

// The next 4 bytes as a float, or 0 past the end.
float next_float(const std::uint8_t*& data, std::size_t& size) {
    float v = 0;
    if (size >= sizeof v) {
        std::memcpy(&v, data, sizeof v);
        data += sizeof v;
        size -= sizeof v;
    }
    return v;
}

kdop::Image image_from(const std::uint8_t*& data, std::size_t& size) {
    kdop::Image image(kWidth, kHeight);
    for (glm::vec4& p : image.pixels) p = {next_float(data, size), next_float(data, size), next_float(data, size), 1};
    return image;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const kdop::HdrFlip flip(67.02064327658226);
    const float exponent = std::abs(next_float(data, size));
    const float exposure = next_float(data, size);
    const kdop::Image reference = image_from(data, size), test = image_from(data, size);

    // The color map: refused naming a pixel, or every mapped value finite.
    if (std::isfinite(exponent) && exponent > 0 && exponent <= 100) {
        const kdop::ColorMap map{kdop::ColorMap::Kind::power, exponent};
        kdop::Image mapped = test;
        auto ok = kdop::map_colors(map, mapped.pixels, mapped.width, "test");
        if (!ok) {
            require(ok.error().message.find("pixel (") != std::string::npos, "a map refusal naming no pixel",
                    ok.error().message);
        } else {
            for (std::size_t i = 0; i < test.pixels.size(); ++i)
                for (int c = 0; c < 3; ++c)
                    if (std::isfinite(test.pixels[i][c]))
                        require(std::isfinite(mapped.pixels[i][c]), "a mapped value beyond float",
                                fmt::format("{} under gamma:{}", test.pixels[i][c], exponent));
        }
    }

    // The tone curves: finite for a finite color at any exposure float can scale by.
    if (std::isfinite(exposure) && std::abs(exposure) <= 126)
        for (kdop::ToneMapper t : {kdop::ToneMapper::aces, kdop::ToneMapper::hable, kdop::ToneMapper::reinhard})
            for (const glm::vec4& p : test.pixels) {
                const glm::vec3 c = glm::max(glm::vec3(p), glm::vec3(0.0f));
                if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b)) continue;
                const glm::vec3 mapped = kdop::tone_map(t, c, std::exp2(exposure));
                for (int i = 0; i < 3; ++i)
                    require(
                        std::isfinite(mapped[i]), "a tone-mapped value that is not finite",
                        fmt::format("{} of ({}, {}, {}) at exposure {}", kdop::to_string(t), c.r, c.g, c.b, exposure));
            }

    // HDR-FLIP: refused with a message, or a finite mean and map in [0, 1].
    auto maps = flip.maps(reference, test, {});
    if (!maps) {
        require(!maps.error().message.empty(), "a refusal without a message", "");
        return 0;
    }
    require(std::isfinite(maps->mean) && maps->mean >= 0 && maps->mean <= 1, "a mean outside [0, 1]",
            fmt::format("{}", maps->mean));
    for (float e : maps->error) require(e >= 0 && e <= 1, "an error outside [0, 1]", fmt::format("{}", e));
    return 0;
}
