// Variant descriptions: which axis set, mode and neighborhood one generated shader implements,
// how variants are named, and how command-line / CMake selections turn into a list of them.
#pragma once

#include "core/result.h"
#include "core/variant_key.h"
#include "generator/axis_set.h"
#include "generator/target_env.h"

#include <kdop/variant.h>

#include <glm/vec2.hpp>

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// How the unrolled form writes its arithmetic; the same function either way. The defaults are
// what measured cheapest on lavapipe (callgrind instructions per pixel, 256x256, clip-n9, see
// `kdop bench`: dop32 467.6, dop22 411.1, dop16-grass 397.7, against 495.6, 422.4, 415.9 for the
// loop form and 527.8, 445.3, 430.8 for fold-dot with trees; measured before the hardening, which
// adds a fixed cost per pixel) and spend the analytic lower bound of float operations in their frame
// (plus 2 per slab in the absolute frame; generator/analytic_cost.h).
struct EmitStyle {
    enum class Projection {
        fold_dot,     // c.x + dot(c.yz, vec2(a, b)): unit component added, dot() over the rest
        multiply_add, // c.x + c.y * a + c.z * b: fused into one Fma per scaled component
        full_dot,     // dot(c, vec3(1.0, a, b)): one dot over the nonzero components
    } projection = Projection::multiply_add;
    enum class Extent {
        tree,    // min/max of all projections as balanced trees
        running, // min/max updated neighbor by neighbor from +-FLT_MAX, as the loop form does from +-1e9
    } extent = Extent::running;

    friend bool operator==(const EmitStyle&, const EmitStyle&) = default;
};

struct VariantSpec {
    AxisSet set; // empty for the gather and copy baselines
    Mode mode;
    Neighborhood neighborhood;
    Form form = Form::unrolled;
    // Applies to both forms. What `kdop stress` found the supplement's formulation needs at the
    // extremes; its price is measured by `kdop bench` (cost.csv, paper_* columns).
    Numerics numerics = Numerics::hardened;
    EmitStyle style = {};
    // What the SPIR-V is built for; the shader text does not depend on it.
    TargetEnv target_env = TargetEnv::vulkan1_0;
    // Whether the shipped SPIR-V drops its names (OpName, OpMemberName) too; kept by default.
    bool strip_names = false;

    VariantKey key() const { return {set.name, mode, neighborhood, form, numerics}; }
};

// The spec's name (variant_key.h): "dop16-grass-varclip-n5", "dop32-clip-n9-loop-paper", "gather-n9".
inline std::string variant_name(const VariantSpec& spec) { return spec.key().name(); }

// Texel offsets of the neighborhood in the order the generated function receives them.
std::span<const glm::ivec2> neighborhood_offsets(Neighborhood n);
// Index of the pixel itself in neighborhood_offsets(n).
int neighborhood_center(Neighborhood n);

inline constexpr Mode kAllModes[] = {Mode::clip, Mode::varclip}; // the clips; see baseline_kernels()
inline constexpr Neighborhood kAllNeighborhoods[] = {Neighborhood::n9, Neighborhood::n5};

// What a selection without --modes or --neighborhoods takes (without --sets: every built-in set).
struct SelectionDefaults {
    std::span<const Mode> modes;
    std::span<const Neighborhood> neighborhoods;
};
// Every variant there is: the registry kdop embeds, kdop-gen and kdop_add_variants, kdop list,
// stress and accuracy, which check or list each variant rather than choose among them.
inline constexpr SelectionDefaults kEveryVariant{kAllModes, kAllNeighborhoods};
// The one default of kdop gen, kdop taa and kdop choose, so the variants one measures and chooses
// among are those another generates: both modes, since a varclip ghosted least on kdop's 3-D scenes
// (dop32-varclip-n9, docs/results.md) and on a team's Blender frames (issue 59), while a clip
// shimmers less, so a default without one would hide the winner; the 3x3 neighborhood only, the
// paper's and an engine's usual, since n5 doubles every measuring run (--neighborhoods n5).
inline constexpr Mode kCommandModes[] = {Mode::clip, Mode::varclip};
inline constexpr Neighborhood kCommandNeighborhoods[] = {Neighborhood::n9};
inline constexpr SelectionDefaults kCommandDefaults{kCommandModes, kCommandNeighborhoods};
// "clip varclip", "n9": a default as its option's help gives it.
std::string default_modes_text(const SelectionDefaults& defaults);
std::string default_neighborhoods_text(const SelectionDefaults& defaults);

// A built-in set by name, or else an axis-set file by path. Errors name the argument.
Result<AxisSet> resolve_axis_set(std::string_view name_or_path);

// The cross product sets x modes x neighborhoods x forms, in that nesting order. Empty lists mean
// `defaults` (for forms: unrolled only). Unknown names, repeated entries and two different sets
// with one name are refused.
Result<std::vector<VariantSpec>> select_variants(const std::vector<std::string>& sets,
                                                 const std::vector<std::string>& modes,
                                                 const std::vector<std::string>& neighborhoods,
                                                 const std::vector<std::string>& forms = {},
                                                 const SelectionDefaults& defaults = kEveryVariant);

// The keys of `specs`, in order.
std::vector<VariantKey> keys_of(const std::vector<VariantSpec>& specs);

// The cost baselines: gather-n9, gather-n5 and copy.
std::vector<VariantSpec> baseline_kernels();

// Every built-in variant: the defaults in both forms, then the baselines (`kdop list --all`).
std::vector<VariantSpec> all_builtin_variants();

} // namespace kdop
