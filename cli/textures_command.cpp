#include "cli/commands.h"

#include "cli/number_option.h"
#include "core/memory_budget.h"
#include "core/shown_text.h"
#include "core/write_files.h"
#include "images/image_io.h"
#include "images/test_textures.h"

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
    textures->add_option("--width", o->width, "Width in pixels")->check(whole_number(8, 16384));
    textures->add_option("--height", o->height, "Height in pixels")->check(whole_number(8, 16384));
    textures->add_option("--seed", o->seed, "Seed of the synthetic textures [default: 1]")->check(seed_number());
    textures->add_flag("--no-real", o->no_real, "Leave out the real textures (colobot-common-textures)");

    return [o] {
        if (auto ok = check_output_directory(o->out); !ok) return report_error(ok.error().message);
        // Every texture and history is made before the first is written: about 48 images at once.
        if (auto ok = check_memory(fmt::format("--width {} --height {}", o->width, o->height),
                                   48 * image_bytes(o->width, o->height));
            !ok)
            return report_error(ok.error().message);
        std::cout << fmt::format("seed {}, {}x{}\n", o->seed, o->width, o->height);
        // Written as a set: a failure halfway leaves none of them.
        const std::vector<TestCase> cases = make_test_cases(o->width, o->height, o->seed, !o->no_real);
        const std::filesystem::path dir(o->out);
        std::vector<ImageFile> images;
        for (std::size_t i = 0; i < cases.size(); ++i) {
            const TestCase& c = cases[i];
            if (i == 0 || c.texture != cases[i - 1].texture) // a texture's first case: its image
                images.push_back({dir / (c.texture + ".exr"), &c.current});
            images.push_back({dir / fmt::format("{}-history-{}.exr", c.texture, to_string(c.model)), &c.history});
        }
        if (auto ok = write_images(images); !ok) return report_error(ok.error().message);
        const std::size_t files = images.size();
        std::cout << fmt::format("wrote {} images to {}\n", files, terminal_text(o->out));
        return 0;
    };
}

} // namespace kdop::cli
