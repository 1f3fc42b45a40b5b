// The test content that reads files: the installed real textures, and every test case with them.
// Apart from texture_cases.cpp because it needs OpenImageIO (kdop_images), which the rest of the
// content does not (kdop_image_content: the runtime and the callgrind probe link that alone).
#include "images/image_io.h"
#include "images/texture_cases.h"

#include <glm/vec3.hpp>

#include <filesystem>

namespace kdop {

std::vector<RealTexture> installed_real_textures() {
    const RealTexture candidates[] = {
        {"colobot-grass", "/usr/share/games/colobot/textures/green01.png"},
        {"colobot-dirt", "/usr/share/games/colobot/textures/dirty01.png"},
        {"colobot-rock", "/usr/share/games/colobot/textures/mars005.png"},
    };
    std::vector<RealTexture> found;
    for (const RealTexture& t : candidates)
        if (std::filesystem::exists(t.path)) found.push_back(t);
    return found;
}

Image load_real_texture(const RealTexture& texture, std::uint32_t w, std::uint32_t h) {
    auto source = read_image_corner(texture.path, w, h); // decoded from sRGB, as the file says
    if (!source) return {};
    Image image(w, h);
    for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x)
            image.at(x, y) = glm::vec4(glm::vec3(source->at(x % source->width, y % source->height)), 1.0f);
    return image;
}

std::vector<TestCase> make_test_cases(std::uint32_t w, std::uint32_t h, std::uint64_t seed, bool real) {
    std::vector<std::pair<std::string, Image>> textures;
    for (TextureFamily f : texture_families()) textures.emplace_back(to_string(f), make_texture(f, w, h, seed));
    if (real)
        for (const RealTexture& t : installed_real_textures()) {
            Image image = load_real_texture(t, w, h);
            if (!image.pixels.empty()) textures.emplace_back(t.name, std::move(image));
        }
    std::vector<TestCase> cases;
    for (std::size_t i = 0; i < textures.size(); ++i) {
        const Image& other = textures[(i + 1) % textures.size()].second;
        for (HistoryModel m : history_models())
            cases.push_back({textures[i].first, m, textures[i].second, make_history(textures[i].second, m, other)});
    }
    return cases;
}

} // namespace kdop
