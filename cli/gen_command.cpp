#include "cli/commands.h"

#include "cli/number_option.h"
#include "core/shown_text.h"
#include "generator/selection_options.h"
#include "generator/spirv_cost.h"
#include "generator/variant_builder.h"
#include "generator/variant_files.h"
#include "harness/progress.h"

#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <memory>

namespace kdop::cli {
namespace {

void print_table(const std::vector<BuiltVariant>& built) {
    std::cout << fmt::format("{:<30} {:>4} {:>11} {:>12} {:>17} {:>9}  {}\n", "variant", "k", "spirv_bytes",
                             "instructions", "code_instructions", "float_ops", "spirv_hash");
    for (const BuiltVariant& v : built)
        std::cout << fmt::format("{:<30} {:>4} {:>11} {:>12} {:>17} {:>9}  {:016x}\n", v.name,
                                 2 * v.spec.set.axes.size(), 4 * v.spirv.size(), v.counts.instructions,
                                 v.counts.function_instructions, count_float_ops(v.spirv).total(), spirv_hash(v.spirv));
}

} // namespace

Action add_gen_command(CLI::App& app) {
    struct Options {
        std::string out;
        SelectionOptions selection;
        unsigned threads = 0;
    };
    auto options = std::make_shared<Options>();
    CLI::App* gen = app.add_subcommand(
        "gen", "Generate variants: write <name>.glsl, .hlsl and .wgsl (includable function), <name>.comp "
               "(compute shader) and <name>.spv (optimized SPIR-V) per variant, then print a table of them");
    gen->add_option("--out", options->out, "Output directory (created if missing)")->required();
    options->selection.add_to(*gen, /*with_manifest=*/true);
    gen->add_option("--threads", options->threads, "Compile on this many threads [default: one per core]")
        ->check(thread_count());

    return [options] {
        auto start = std::chrono::steady_clock::now();
        if (auto ok = check_output_directory(options->out); !ok) return report_error(ok.error().message);
        auto specs = options->selection.select();
        if (!specs) return report_error(specs.error().message);

        Progress progress("built", specs->size());
        auto built = build_variants(*specs, options->threads,
                                    [&](std::size_t, std::size_t, const std::string& name) { progress.advance(name); });
        progress.finish();
        if (!built) return report_error(built.error().message);

        std::vector<OutputFile> files;
        for (const BuiltVariant& v : *built) {
            for (OutputFile& f : glsl_files(v, options->out)) files.push_back(std::move(f));
            files.push_back(spirv_file(v, options->out));
        }
        if (auto ok = write_files_atomically(files); !ok) return report_error(ok.error().message);

        print_table(*built);
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::cout << fmt::format("\nwrote {} files for {} variants to {} in {:.2f} s\n", files.size(), built->size(),
                                 terminal_text(options->out), seconds);
        return 0;
    };
}

} // namespace kdop::cli
