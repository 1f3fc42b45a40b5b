// The formats a rectify pass's input textures come in, and how an image's pixels are laid out for
// upload in each: what the pass (runtime/rectify_pass.h) and its callers name on a command line.
#pragma once

#include "images/image.h"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace kdop {

enum class TextureFormat {
    rgba32f,
    rgba16f, // values are rounded to half precision on upload (beyond 65504 they become infinite)
};
std::optional<TextureFormat> parse_texture_format(std::string_view s);
const char* to_string(TextureFormat format);

// The Vulkan format of a texture of `channels` (1, 2 or 4) in `format` (fewer than four: rgba32f only).
VkFormat vk_format(TextureFormat format, std::uint32_t channels);
// The bytes of one texel of `channels` in `format`.
VkDeviceSize texel_bytes(TextureFormat format, std::uint32_t channels);
// The first `channels` of each pixel of `image`, in `format`, at `to` (texel_bytes each).
void pack(const Image& image, TextureFormat format, std::uint32_t channels, std::byte* to);

} // namespace kdop
