#include "commands.h"

#include "cost_bench.h"
#include "cost_report.h"
#include "write_files.h"
#include "run_info.h"
#include "scratch_directory.h"

#include <kdop_builtin_variants.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <optional>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

namespace kdop::cli {
namespace {

// "1920x1080" -> {1920, 1080}; both sides 8..16384.
std::optional<bench::Size> parse_size(std::string_view text) {
    const auto x = text.find('x');
    if (x == std::string_view::npos) return std::nullopt;
    auto number = [](std::string_view s) -> std::optional<std::uint32_t> {
        std::uint32_t v = 0;
        auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (error != std::errc{} || end != s.data() + s.size() || v < 8 || v > 16384) return std::nullopt;
        return v;
    };
    auto w = number(text.substr(0, x)), h = number(text.substr(x + 1));
    if (!w || !h) return std::nullopt;
    return bench::Size{*w, *h};
}

} // namespace

Action add_bench_command(CLI::App& app) {
    struct Options {
        std::string out, size = "1920x1080", device;
        std::vector<std::string> variants, sweep_sizes{"256x256", "512x512", "1024x1024", "1920x1080", "2560x1440", "3840x2160"};
        unsigned repeat = 15, sweep_repeat = 5, callgrind_size = 256, jobs = std::max(1u, std::thread::hardware_concurrency());
        bool no_sweep = false, no_callgrind = false;
    };
    auto o = std::make_shared<Options>();
    CLI::App* bench = app.add_subcommand(
        "bench", "Measure what each variant costs: static float-op counts against the loop form and the analytic minimum, "
                 "interleaved timings, a size sweep and callgrind instruction counts; writes cost.csv, report.md and charts");
    bench->add_option("--out", o->out, "Output directory (created if missing)")->required();
    bench->add_option("--variants", o->variants, "Unrolled default variants to measure, with their loop forms [default: all 24]");
    bench->add_option("--size", o->size, "Timing size WIDTHxHEIGHT [default: 1920x1080]");
    bench->add_option("--repeat", o->repeat, "Dispatches per kernel at the timing size (interleaved rounds) [default: 15]")
        ->check(CLI::Range(1u, 10000u));
    bench->add_option("--sweep-sizes", o->sweep_sizes, "Sizes of the size sweep [default: 256x256 ... 3840x2160]");
    bench->add_option("--sweep-repeat", o->sweep_repeat, "Rounds per sweep size [default: 5]")->check(CLI::Range(1u, 10000u));
    bench->add_flag("--no-sweep", o->no_sweep, "Skip the size sweep");
    bench->add_option("--callgrind-size", o->callgrind_size, "Callgrind dispatch size N (NxN pixels) [default: 256]")
        ->check(CLI::Range(8u, 4096u));
    bench->add_flag("--no-callgrind", o->no_callgrind, "Skip the callgrind instruction counts");
    bench->add_option("--jobs", o->jobs, "Callgrind runs at a time [default: one per core]")->check(CLI::Range(1u, 256u));
    bench->add_option("--device", o->device, "Vulkan device: a substring of its name [default: $KDOP_DEVICE, else lavapipe]");

    return [o] {
        bench::BenchOptions options;
        if (o->variants.empty())
            for (const Variant& v : builtin::variants())
                if (v.form == Form::unrolled && (v.mode == Mode::clip || v.mode == Mode::varclip))
                    options.variants.push_back(v.name);
        for (const std::string& name : o->variants) {
            const Variant* v = builtin::variants().find(name.c_str());
            if (!v || v->form != Form::unrolled || (v->mode != Mode::clip && v->mode != Mode::varclip))
                return report_error(fmt::format("--variants: '{}' is not a default clip variant (see `kdop list`)", name));
            if (std::ranges::find(options.variants, name) != options.variants.end())
                return report_error(fmt::format("--variants: '{}' is given twice", name));
            options.variants.push_back(name);
        }
        auto size = parse_size(o->size);
        if (!size) return report_error(fmt::format("--size: '{}' is not WIDTHxHEIGHT with sides 8..16384", o->size));
        options.timing_size = *size;
        options.rounds = o->repeat;
        if (!o->no_sweep)
            for (const std::string& text : o->sweep_sizes) {
                auto s = parse_size(text);
                if (!s) return report_error(fmt::format("--sweep-sizes: '{}' is not WIDTHxHEIGHT with sides 8..16384", text));
                options.sweep_sizes.push_back(*s);
            }
        options.sweep_rounds = o->sweep_repeat;
        options.callgrind = !o->no_callgrind;
        options.callgrind_size = o->callgrind_size;
        options.jobs = o->jobs;
        options.device = o->device;
        options.probe = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "kdop-dispatch-probe";
        if (options.callgrind && !std::filesystem::exists(options.probe))
            return report_error(fmt::format("{} is missing (it is built with kdop); or pass --no-callgrind",
                                            options.probe.string()));
        bench::ScratchDirectory scratch("kdop-bench");
        if (scratch.path.empty()) return report_error("cannot create a scratch directory in the temporary directory");
        options.scratch = scratch.path;

        auto result = bench::run_cost_bench(options);
        if (!result) return report_error(result.error().message);

        bench::ReportContext context{bench::utc_now_iso8601(), bench::source_commit(), bench::machine_description(),
                                     "", options};
        context.command = fmt::format("kdop bench --out {} --size {}x{} --repeat {}{}{}{}", o->out, size->first,
                                      size->second, o->repeat,
                                      o->variants.empty() ? "" : fmt::format(" --variants {}", fmt::join(o->variants, " ")),
                                      o->no_sweep ? " --no-sweep" : fmt::format(" --sweep-repeat {}", o->sweep_repeat),
                                      o->no_callgrind ? " --no-callgrind" : fmt::format(" --callgrind-size {}", o->callgrind_size));
        const std::filesystem::path dir = o->out;
        auto charts = bench::cost_charts(*result, scratch.path, dir);
        if (!charts) return report_error(charts.error().message);
        std::vector<OutputFile> files{{dir / "cost.csv", bench::cost_csv(result->rows)},
                                      {dir / "report.md", bench::cost_report_markdown(*result, context)}};
        files.insert(files.end(), charts->begin(), charts->end());
        if (auto ok = write_files_atomically(files); !ok) return report_error(ok.error().message);
        std::cout << fmt::format("wrote {} files to {} ({} variants on {})\n", files.size(), o->out, options.variants.size(),
                                 result->device_name);
        return 0;
    };
}

} // namespace kdop::cli
