#include "cli/commands.h"

#include "cli/number_option.h"
#include "core/shown_text.h"
#include "generator/selection_options.h"
#include "generator/spirv_cost.h"
#include "generator/variant_builder.h"
#include "generator/variant_files.h"
#include "harness/printed_table.h"
#include "harness/progress.h"

#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <memory>

namespace kdop::cli {
namespace {

// One row per variant: its size and counts, and the hash a build reproduces.
const PrintedColumns<BuiltVariant> kVariantColumns{
    {"variant", -30, [](const BuiltVariant& v) { return v.name; }},
    {"k", 4, [](const BuiltVariant& v) { return fmt::format("{}", 2 * v.spec.set.axes.size()); }},
    {"spirv_bytes", 11, [](const BuiltVariant& v) { return fmt::format("{}", 4 * v.spirv.size()); }},
    {"instructions", 12, [](const BuiltVariant& v) { return fmt::format("{}", v.counts.instructions); }},
    {"code_instructions", 17, [](const BuiltVariant& v) { return fmt::format("{}", v.counts.function_instructions); }},
    {"float_ops", 9, [](const BuiltVariant& v) { return fmt::format("{}", count_float_ops(v.spirv).total()); }},
    {"spirv_hash", 0, [](const BuiltVariant& v) { return fmt::format("{:016x}", spirv_hash(v.spirv)); }, "  "}};

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
               "(compute shader) and <name>.spv (optimized SPIR-V) per variant and their reflection as "
               "variants.json, then print a table of them");
    gen->add_option("--out", options->out, "Output directory (created if missing)")->required();
    options->selection.add_to(*gen, /*with_manifest=*/true, kCommandDefaults);
    gen->add_option("--threads", options->threads, "Compile on this many threads [default: one per core]")
        ->check(thread_count());

    return [options] {
        auto start = std::chrono::steady_clock::now();
        if (auto ok = check_output_directory(options->out); !ok) return report_error(ok.error().message);
        auto specs = options->selection.select();
        if (!specs) return report_error(specs.error().message);
        auto resolve = options->selection.resolve();
        if (!resolve) return report_error(resolve.error().message);

        Progress progress("built", specs->size());
        auto generated = generate_variants(
            *specs, options->out, options->threads,
            [&](std::size_t, std::size_t, const std::string& name) { progress.advance(name); }, *resolve);
        progress.finish();
        if (!generated) return report_error(generated.error().message);
        std::cout << printed_header(kVariantColumns) << "\n";
        for (const BuiltVariant& v : generated->built) std::cout << printed_row(kVariantColumns, v) << "\n";
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::cout << fmt::format("\nwrote {} files for {} variants to {} in {:.2f} s\n", generated->files,
                                 generated->built.size(), terminal_text(options->out), seconds);
        return 0;
    };
}

} // namespace kdop::cli
