// A renderer's own resolve measured in place of kdop's (temporal/own_resolve.h): --resolve,
// --resolve-bindings and --hlsl-entry, for the commands that measure a resolve (taa, choose).
#pragma once

#include "temporal/own_resolve.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <optional>
#include <string>

namespace kdop::cli {

struct OwnResolveOptions {
    std::string shader, bindings, hlsl_entry = "main";
    CLI::Option *shader_option = nullptr, *bindings_option = nullptr, *entry_option = nullptr;
};

inline void add_own_resolve_options(CLI::App& app, OwnResolveOptions& o) {
    o.shader_option = app.add_option(
        "--resolve", o.shader,
        "Measure your own TAA or TAAU resolve instead of kdop's: a compute shader in GLSL (.comp) or HLSL "
        "(.cs.hlsl) that includes \"kdop_variant.glsl\" (.hlsl) and clips with kdop_rectify(current, history, "
        "gamma, neighborhood), built once per variant; needs --resolve-bindings (docs/taa.md, \"Your own resolve\")");
    o.bindings_option = app.add_option("--resolve-bindings", o.bindings,
                                       "With --resolve: the map (JSON, docs/resolve-bindings.schema.json) of what each "
                                       "of the shader's resources, push-constant and uniform-block members is");
    o.entry_option =
        app.add_option("--hlsl-entry", o.hlsl_entry, "With an HLSL --resolve: its entry point [default: main]");
}

// The resolve the options name, or none. A usage error (`usage`, for exit 2) where one of
// --resolve and --resolve-bindings is given without the other, --hlsl-entry without an HLSL
// --resolve, or with one of kdop's own resolve's options its shader has no counterpart of
// (`app`'s); a file that cannot be read or a map that does not parse is an input error (`input`).
struct OwnResolveChoice {
    std::optional<OwnResolve> resolve;
    std::string usage, input;
};
inline OwnResolveChoice own_resolve_choice(const CLI::App& app, const OwnResolveOptions& o) {
    OwnResolveChoice choice;
    if (o.shader_option->count() != o.bindings_option->count()) {
        choice.usage = o.shader_option->count() ? "--resolve: needs --resolve-bindings, the map of its roles"
                                                : "--resolve-bindings: is the map of a --resolve, and none is given";
        return choice;
    }
    if (o.entry_option->count() && !o.shader.ends_with(".hlsl")) {
        choice.usage = "--hlsl-entry: names the entry point of an HLSL --resolve (.cs.hlsl), and none is given";
        return choice;
    }
    if (!o.shader_option->count()) return choice;
    // Defines of kdop's resolve: a renderer's shader does these its own way.
    for (const char* option : {"--history-filter", "--color-map", "--dilate-motion", "--upscale-filter"})
        if (app.count(option)) {
            choice.usage = fmt::format("{}: is an option of kdop's own resolve; --resolve measures yours, which "
                                       "does it its own way",
                                       option);
            return choice;
        }
    auto resolve = load_own_resolve(o.shader, o.bindings, o.hlsl_entry);
    if (!resolve)
        choice.input = resolve.error().message;
    else
        choice.resolve = std::move(*resolve);
    return choice;
}

} // namespace kdop::cli
