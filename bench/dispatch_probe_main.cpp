// kdop-dispatch-probe: runs one variant's dispatch with callgrind instrumentation around exactly
// that dispatch, so `valgrind --tool=callgrind --instr-atstart=no` counts the CPU instructions
// lavapipe executes for it and nothing else (context, upload, pipeline compile and one warm-up
// dispatch stay outside). Run with LP_NUM_THREADS=0 so the dispatch runs on this thread.
// The bench (kdop bench) starts it; it is not meant to be run by hand.
#include "bench/bench_inputs.h"
#include "runtime/context.h"
#include "runtime/kernel.h"
#include "runtime/rectify_pass.h"

#include <kdop_builtin_variants.h>

#include <CLI/CLI.hpp>
#include <valgrind/callgrind.h>

#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>

int main(int argc, char** argv) {
    using namespace kdop;
    CLI::App app{"kdop-dispatch-probe: one instrumented dispatch, for callgrind"};
    std::string name;
    std::uint32_t width = 256, height = 256;
    std::string spirv_path, device;
    app.add_option("--variant", name, "Registry variant to run (its interface, and its SPIR-V unless --spirv)")
        ->required();
    app.add_option("--spirv", spirv_path, "Run this SPIR-V module instead, with the variant's interface");
    app.add_option("--width", width)->check(CLI::Range(8u, 8192u));
    app.add_option("--height", height)->check(CLI::Range(8u, 8192u));
    app.add_option("--device", device, "Vulkan device: a substring of its name [default: lavapipe]");
    CLI11_PARSE(app, argc, argv);

    const Variant* registered = builtin::variants().find(name.c_str());
    if (!registered) {
        std::cerr << "--variant: unknown variant '" << name << "'\n";
        return 1;
    }
    Variant replaced = *registered;
    std::vector<std::uint32_t> words;
    if (!spirv_path.empty()) {
        std::ifstream in(spirv_path, std::ios::binary);
        std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (!in.good() && !in.eof()) return std::cerr << spirv_path << ": cannot read\n", 1;
        words.resize(bytes.size() / 4);
        std::memcpy(words.data(), bytes.data(), words.size() * 4);
        replaced.spirv = words.data();
        replaced.spirv_word_count = words.size();
    }
    const Variant* variant = &replaced;
    auto [current, history] = bench::bench_inputs(width, height);
    auto context = Context::create({device, false});
    auto kernel = context ? Kernel::create(**context, *variant) : std::unexpected(context.error());
    auto pass = context ? RectifyPass::create(**context, width, height, TextureFormat::rgba32f)
                        : std::unexpected(context.error());
    if (!kernel || !pass) {
        std::cerr << (kernel ? pass.error() : kernel.error()).message << '\n';
        return 1;
    }
    if (auto ok = (*pass)->upload(current, history); !ok) return std::cerr << ok.error().message << '\n', 1;
    if (auto warm = (*pass)->dispatch(**kernel, 1.0f); !warm) return std::cerr << warm.error().message << '\n', 1;

    CALLGRIND_ZERO_STATS;
    CALLGRIND_START_INSTRUMENTATION;
    auto timing = (*pass)->dispatch(**kernel, 1.0f);
    CALLGRIND_STOP_INSTRUMENTATION;
    CALLGRIND_DUMP_STATS_AT("dispatch");
    if (!timing) return std::cerr << timing.error().message << '\n', 1;
    return 0;
}
