#include "commands.h"

#include "image_io.h"
#include "memory_budget.h"
#include "test_textures.h"
#include "write_files.h"

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
        if (auto ok = check_output_directory(o->out); !ok) return report_error(ok.error().message);
        // Every texture and history is made before the first is written: about 48 images at once.
        if (auto ok = check_memory(fmt::format("--width {} --height {}", o->width, o->height),
                                   48 * image_bytes(o->width, o->height));
            !ok)
            return report_error(ok.error().message);
        std::cout << fmt::format("seed {}, {}x{}\n", o->seed, o->width, o->height);
        std::error_code error;
        std::filesystem::create_directories(o->out, error);
        if (error) return report_error(fmt::format("--out: {}: {}", o->out, error.message()));
        std::string last_texture;
        int files = 0;
        for (const TestCase& c : make_test_cases(o->width, o->height, o->seed, !o->no_real)) {
            std::filesystem::path dir(o->out);
            if (c.texture != last_texture) {
                if (auto ok = write_image((dir / (c.texture + ".exr")).string(), c.current); !ok)
                    return report_error(ok.error().message);
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
