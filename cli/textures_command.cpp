#include "cli/commands.h"

#include "cli/number_option.h"
#include "core/memory_budget.h"
#include "core/shown_text.h"
#include "core/write_files.h"
#include "images/texture_cases.h"

#include <fmt/format.h>

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
        auto written = write_test_cases(make_test_cases(o->width, o->height, o->seed, !o->no_real), o->out);
        if (!written) return report_error(written.error().message);
        std::cout << fmt::format("wrote {} images to {}\n", *written, terminal_text(o->out));
        return 0;
    };
}

} // namespace kdop::cli
