// Neighborhood test content: seeded synthetic texture families, real game textures when Debian's
// colobot-common-textures is installed, and history images that model ghosting. The same seed
// and size give the same pixels on every machine (see random.h). The synthetic content is in
// kdop_image_content; what reads files (the real textures, make_test_cases) in kdop_images.
#pragma once

#include "core/result.h"
#include "images/image.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace kdop {

enum class TextureFamily {
    grass,      // high-frequency chroma and luma: yellow- to blue-green blades with dark gaps
    asphalt,    // high-frequency luma on gray: grain, bright aggregate and dark pits
    edges,      // hard edges between saturated flat shapes
    gradient,   // smooth color ramps, no noise
    flat,       // large constant areas: mid gray 0.37, a saturated color, black, and bright (40)
    hdr,        // a dim scene with highlights from 5 to 60000
    highlights, // grass with 3% of its pixels raised to highlights from 1e2 to 5e4 of any hue
};
std::span<const TextureFamily> texture_families();
const char* to_string(TextureFamily family);

Image make_texture(TextureFamily family, std::uint32_t width, std::uint32_t height, std::uint64_t seed);

enum class HistoryModel {
    same,          // history equals current: nothing to clip
    shifted,       // current moved by (3, 2) pixels, as after a camera pan
    moved_object,  // a red object (with dark tires) stood here last frame; the rest slightly shifted
    other_texture, // a different texture entirely, as on disocclusion
};
std::span<const HistoryModel> history_models();
const char* to_string(HistoryModel model); // "same", "shifted", "moved-object", "other-texture"

// `other` is the content used by other_texture and ignored otherwise; same size as `current`.
Image make_history(const Image& current, HistoryModel model, const Image& other);

struct RealTexture {
    std::string name; // e.g. "colobot-grass"
    std::string path;
};
// The real textures installed on this machine (none without colobot-common-textures).
std::vector<RealTexture> installed_real_textures();

// A real texture decoded from sRGB to linear and tiled or cropped to the size; empty on failure.
Image load_real_texture(const RealTexture& texture, std::uint32_t width, std::uint32_t height);

struct TestCase {
    std::string texture; // family or real texture name
    HistoryModel model;
    Image current, history;
    std::string name() const { return texture + "/" + to_string(model); }
};

// Every synthetic family x history model, then (when `real`) every installed real texture x model.
// other_texture takes the next texture in the list as history.
std::vector<TestCase> make_test_cases(std::uint32_t width, std::uint32_t height, std::uint64_t seed, bool real = true);

// `kdop textures`: every case's texture (once) and history as EXR in `dir`, <texture>.exr and
// <texture>-history-<model>.exr, written as a set (a failure halfway leaves none). Returns how
// many files were written. In kdop_images (texture_case_files.cpp).
Result<std::size_t> write_test_cases(const std::vector<TestCase>& cases, const std::filesystem::path& dir);

} // namespace kdop
