// The --sets / --modes / --neighborhoods options shared by kdop and kdop-gen, so both accept and
// describe a selection of variants the same way.
#pragma once

#include "builtin_sets.h"
#include "variant_spec.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace kdop {

struct SelectionOptions {
    std::vector<std::string> sets, modes, neighborhoods, forms;
    bool baselines = false;
    std::string projection = "multiply-add", extent = "running", numerics = "hardened";

    void add_to(CLI::App& app) {
        app.add_option("--sets", sets,
                       "Axis sets: built-in names (" + builtin_set_list() +
                           ") or paths to .axes files [default: every built-in set]");
        app.add_option("--modes", modes, "clip and/or varclip [default: both]");
        app.add_option("--neighborhoods", neighborhoods, "n9 (3x3) and/or n5 (plus) [default: both]");
        app.add_option("--forms", forms,
                       "unrolled and/or loop (the supplement's loop form, named <variant>-loop) [default: unrolled]");
        app.add_flag("--baselines", baselines, "Also the cost baselines gather-n9, gather-n5 and copy");
        app.add_option("--projection", projection,
                       "How unrolled projections are written: fold-dot, multiply-add or full-dot")
            ->check(CLI::IsMember({"fold-dot", "multiply-add", "full-dot"}));
        app.add_option("--extent", extent, "How unrolled slab extents are reduced: tree or running")
            ->check(CLI::IsMember({"tree", "running"}));
        app.add_option("--numerics", numerics,
                       "hardened, or paper for the supplement's numerics without kdop's fixes for HDR, flat and "
                       "NaN input (named <variant>-paper; see `kdop stress`)")
            ->check(CLI::IsMember({"hardened", "paper"}));
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

    Result<std::vector<VariantSpec>> select() const {
        auto specs = select_variants(sets, modes, neighborhoods, forms);
        if (specs)
            for (VariantSpec& s : *specs) {
                s.style = style();
                s.numerics = *parse_numerics(numerics); // checked by CLI11
            }
        if (specs && baselines)
            for (VariantSpec& b : baseline_kernels()) specs->push_back(std::move(b));
        return specs;
    }
};

} // namespace kdop
