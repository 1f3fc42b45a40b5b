// The --sets / --modes / --neighborhoods options (and how to write and build them: --projection,
// --extent, --numerics, --target-env, --strip-names) shared by kdop and kdop-gen, so both accept and describe a
// selection of variants the same way.
#pragma once

#include "core/builtin_sets.h"
#include "core/shown_text.h"
#include "generator/manifest.h"
#include "generator/variant_spec.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace kdop {

struct SelectionOptions {
    std::vector<std::string> sets, modes, neighborhoods, forms;
    bool baselines = false;
    std::string projection = "multiply-add", extent = "running", numerics = "hardened", target_env = "vulkan1.0";
    std::string manifest; // a scene's variant manifest (manifest.h), instead of the cross product
    bool strip_names = false;
    // What the command selects without --modes or --neighborhoods: every variant, or the default of
    // kdop gen, taa and choose (variant_spec.h).
    SelectionDefaults defaults = kEveryVariant;

    // `with_manifest`: also --manifest FILE, which excludes the options that select by cross product.
    void add_to(CLI::App& app, bool with_manifest = false, const SelectionDefaults& selected = kEveryVariant) {
        defaults = selected;
        std::vector<CLI::Option*> cross_product{
            app.add_option("--sets", sets,
                           "Axis sets: built-in names (" + builtin_set_list() +
                               ") or paths to .axes files [default: every built-in set]")
                ->check(axis_set_name()),
            app.add_option("--modes", modes, "clip and/or varclip [default: " + default_modes_text(defaults) + "]")
                ->check(choice("mode", "clip or varclip", parse_mode)),
            app.add_option("--neighborhoods", neighborhoods,
                           "n9 (3x3) and/or n5 (plus) [default: " + default_neighborhoods_text(defaults) + "]")
                ->check(choice("neighborhood", "n9 or n5", parse_neighborhood)),
            app.add_option(
                   "--forms", forms,
                   "unrolled and/or loop (the supplement's loop form, named <variant>-loop) [default: unrolled]")
                ->check(choice("form", "unrolled or loop", parse_form)),
            app.add_flag("--baselines", baselines, "Also the cost baselines gather-n9, gather-n5 and copy")};
        app.add_option("--projection", projection,
                       "How unrolled projections are written: fold-dot, multiply-add or full-dot")
            ->check(CLI::IsMember({"fold-dot", "multiply-add", "full-dot"}));
        app.add_option("--extent", extent, "How unrolled slab extents are reduced: tree or running")
            ->check(CLI::IsMember({"tree", "running"}));
        cross_product.push_back(
            app.add_option("--numerics", numerics,
                           "hardened, or paper for the supplement's numerics without kdop's fixes for HDR, flat and "
                           "NaN input (named <variant>-paper; see `kdop stress`)")
                ->check(CLI::IsMember({"hardened", "paper"})));
        app.add_option("--target-env", target_env,
                       "Vulkan version the SPIR-V is built and validated for: vulkan1.0 (SPIR-V 1.0, any device), "
                       "vulkan1.1 (1.3), vulkan1.2 (1.5) or vulkan1.3 (1.6)")
            ->check(CLI::IsMember({"vulkan1.0", "vulkan1.1", "vulkan1.2", "vulkan1.3"}));
        app.add_flag("--strip-names", strip_names,
                     "Drop the names (OpName, OpMemberName) from the SPIR-V, for shipping; kept by default, as glslc "
                     "keeps them, so spirv-cross output and RenderDoc read with the shader's names");
        if (with_manifest) {
            CLI::Option* option =
                app.add_option("--manifest", manifest,
                               "Exactly the variants a scene's manifest lists (one variant name per line; `set: FILE` "
                               "lines add axis files; see docs/embedding.md)");
            for (CLI::Option* other : cross_product) option->excludes(other);
        }
    }

    // A --sets entry: a built-in set's name or a file that exists (what it holds is the file's to
    // say, when it is read), so a mistyped name is a wrong command line, exit 2.
    static CLI::Validator axis_set_name() {
        return CLI::Validator(
            [](std::string& text) -> std::string {
                std::error_code ec;
                if (is_builtin_set(text) || std::filesystem::exists(text, ec)) return {};
                return "'" + shown_text(text, 80) + "' is not a built-in axis set (" + builtin_set_list() +
                       ") nor a file";
            },
            "SET");
    }

    // A value `parse` takes, refused in select_variants' words: "unknown mode 'clamp' (expected clip
    // or varclip)".
    template <class T>
    static CLI::Validator choice(const char* what, const char* expected, std::optional<T> (*parse)(std::string_view)) {
        return CLI::Validator(
            [=](std::string& text) -> std::string {
                if (parse(text)) return {};
                return std::string("unknown ") + what + " '" + shown_text(text, 80) + "' (expected " + expected + ")";
            },
            expected);
    }

    // --projection and --extent.
    EmitStyle style() const {
        EmitStyle style;
        style.projection = projection == "multiply-add" ? EmitStyle::Projection::multiply_add
                           : projection == "full-dot"   ? EmitStyle::Projection::full_dot
                                                        : EmitStyle::Projection::fold_dot;
        style.extent = extent == "running" ? EmitStyle::Extent::running : EmitStyle::Extent::tree;
        return style;
    }

    // The sets a VariantCatalog must be told of to find the selection: --sets, or the manifest's
    // `set:` files.
    Result<std::vector<std::string>> set_sources() const {
        if (manifest.empty()) return sets;
        auto listed = read_manifest(manifest);
        if (!listed) return std::unexpected(listed.error());
        std::vector<std::string> files;
        for (const std::filesystem::path& file : listed->set_files) files.push_back(file.string());
        return files;
    }

    // The TAA resolve the manifest records its variants were measured with (manifest.h); none
    // without a manifest or where it records none.
    Result<std::optional<ResolveSettings>> resolve() const {
        if (manifest.empty()) return std::optional<ResolveSettings>();
        auto listed = read_manifest(manifest);
        if (!listed) return std::unexpected(listed.error());
        return listed->resolve;
    }

    Result<std::vector<VariantSpec>> select() const {
        if (!manifest.empty()) {
            auto listed = read_manifest(manifest);
            if (!listed) return std::unexpected(listed.error());
            for (VariantSpec& s : listed->variants) {
                s.style = style();
                s.target_env = *parse_target_env(target_env); // checked by CLI11
                s.strip_names = strip_names;
            }
            return std::move(listed->variants);
        }
        auto specs = select_variants(sets, modes, neighborhoods, forms, defaults);
        if (specs)
            for (VariantSpec& s : *specs) {
                s.style = style();
                s.numerics = *parse_numerics(numerics);       // checked by CLI11
                s.target_env = *parse_target_env(target_env); // checked by CLI11
                s.strip_names = strip_names;
            }
        if (specs && baselines)
            for (VariantSpec& b : baseline_kernels()) {
                b.target_env = *parse_target_env(target_env);
                b.strip_names = strip_names;
                specs->push_back(std::move(b));
            }
        return specs;
    }
};

} // namespace kdop
