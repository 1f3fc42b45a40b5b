// A scene's variant manifest: exactly the variants a scene uses, so a build generates and embeds
// those and no others (`kdop gen --manifest`, `kdop list --manifest`, `kdop-gen registry
// --manifest`, kdop_add_variants(MANIFEST)).
//
//     # The forest level: its fitted set, and the general 22-DOP for the sky.
//     set: axes/forest.axes          # an axis file, relative to this manifest; its variants by its name
//     forest-clip-n9
//     forest-varclip-n5-paper        # any variant name: set, mode, neighborhood, [-loop], [-paper]
//     dop22-clip-n9                  # built-in sets need no `set:` line
//
// One entry per line; '#' starts a comment. A name that is not a variant, a set that is neither
// built in nor given by a `set:` line, a variant listed twice and two sets of one name are errors
// naming the manifest's line.
//
// It may also record the TAA resolve its variants were measured with, as kdop choose's does, in
// five `key: value` lines anywhere in it, spelled as the options of kdop taa and kdop choose:
//
//     gamma: 1                  # the variance clip's width: a number above 0, at most 100
//     current-weight: 0.1       # the current frame's share of the blend: above 0, at most 1
//     color-map: linear         # linear, gamma:G (G from 0.01 to 100) or log
//     history-filter: bilinear  # bilinear or catmull-rom
//     dilate-motion: no         # yes or no
//
// All five or none (a resolve half recorded would leave the rest to a guess), each once; numbers
// are decimals. Where the variants were judged through an upscaling resolve, three more lines say
// how it upscaled, all three or none:
//
//     upscale-filter: lanczos2      # lanczos2 or gaussian
//     upscale-sample-distance: all  # all, ue4 or a number of input pixels above 0, at most 4
//     upscale-box-scale: none       # none or fsr2
// kdop-gen gives them to the build (the registry's `resolve_settings`, the
// reflection's "resolve"). An unknown key, a value out of range and a key given twice are errors
// naming the line.
#pragma once

#include "core/result.h"
#include "generator/variant_spec.h"

#include <kdop/variant.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

struct Manifest {
    std::vector<VariantSpec> variants;            // in the manifest's order
    std::vector<std::filesystem::path> set_files; // the `set:` files, as the manifest resolves them
    std::optional<ResolveSettings> resolve;       // its resolve lines; none where it has none
};

Result<Manifest> read_manifest(const std::filesystem::path& path);

// The five lines that record `resolve` (and the three of an upscaling one), in the order above, each value in the
// fewest digits that read back as the same float (or double, for the color map's exponent): what read_manifest reads.
std::string resolve_lines(const ResolveSettings& resolve);
// The color map as the color-map: line and --color-map spell it: "linear", "gamma:2.2", "log".
std::string color_map_text(const ResolveSettings& resolve);

} // namespace kdop
