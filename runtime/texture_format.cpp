#include "runtime/texture_format.h"

#include <glm/gtc/packing.hpp>

#include <cstring>

namespace kdop {

std::optional<TextureFormat> parse_texture_format(std::string_view s) {
    if (s == "rgba32f") return TextureFormat::rgba32f;
    if (s == "rgba16f") return TextureFormat::rgba16f;
    return std::nullopt;
}

const char* to_string(TextureFormat format) { return format == TextureFormat::rgba16f ? "rgba16f" : "rgba32f"; }

VkFormat vk_format(TextureFormat format, std::uint32_t channels) {
    if (format == TextureFormat::rgba16f) return VK_FORMAT_R16G16B16A16_SFLOAT;
    return channels == 1   ? VK_FORMAT_R32_SFLOAT
           : channels == 2 ? VK_FORMAT_R32G32_SFLOAT
                           : VK_FORMAT_R32G32B32A32_SFLOAT;
}

VkDeviceSize texel_bytes(TextureFormat format, std::uint32_t channels) {
    return (format == TextureFormat::rgba16f ? 2 : 4) * VkDeviceSize(channels);
}

void pack(const Image& image, TextureFormat format, std::uint32_t channels, std::byte* to) {
    const std::size_t pixels = image.pixels.size();
    if (format == TextureFormat::rgba16f) {
        auto* halves = reinterpret_cast<std::uint64_t*>(to);
        for (std::size_t k = 0; k < pixels; ++k) halves[k] = glm::packHalf4x16(image.pixels[k]);
    } else if (channels == 4) {
        std::memcpy(to, image.pixels.data(), pixels * 16);
    } else {
        auto* floats = reinterpret_cast<float*>(to);
        for (std::size_t k = 0; k < pixels; ++k)
            for (std::uint32_t c = 0; c < channels; ++c) floats[k * channels + c] = image.pixels[k][int(c)];
    }
}

} // namespace kdop
