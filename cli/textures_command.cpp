#include "commands.h"

#include "image_io.h"
#include "test_textures.h"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>

namespace kdop::cli {

Action add_textures_command(CLI::App& app) {
    struct Options {
        std::string out;
        std::uint32_t width = 256, height = 256;
        std::uint64_t seed = 1;
        bool no_real = false;
    };
    auto o = std::make_shared<Options>();
    CLI::App* textures = app.add_subcommand(
        "textures", "Write the neighborhood test textures and their ghosting histories as EXR: <texture>.exr and "
                    "<texture>-history-<model>.exr");
    textures->add_option("--out", o->out, "Output directory (created if missing)")->required();
    textures->add_option("--width", o->width, "Width in pixels")->check(CLI::Range(8u, 16384u));
    textures->add_option("--height", o->height, "Height in pixels")->check(CLI::Range(8u, 16384u));
    textures->add_option("--seed", o->seed, "Seed of the synthetic textures [default: 1]");
    textures->add_flag("--no-real", o->no_real, "Leave out the real textures (colobot-common-textures)");

    return [o] {
        std::cout << fmt::format("seed {}, {}x{}\n", o->seed, o->width, o->height);
        std::filesystem::create_directories(o->out);
        std::string last_texture;
        int files = 0;
        for (const TestCase& c : make_test_cases(o->width, o->height, o->seed, !o->no_real)) {
            std::filesystem::path dir(o->out);
            if (c.texture != last_texture) {
                if (auto ok = write_image((dir / (c.texture + ".exr")).string(), c.current); !ok) return report_error(ok.error().message);
                last_texture = c.texture;
                ++files;
            }
            auto path = dir / fmt::format("{}-history-{}.exr", c.texture, to_string(c.model));
            if (auto ok = write_image(path.string(), c.history); !ok) return report_error(ok.error().message);
            ++files;
        }
        std::cout << fmt::format("wrote {} images to {}\n", files, o->out);
        return 0;
    };
}

} // namespace kdop::cli
