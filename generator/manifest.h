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
#pragma once

#include "core/result.h"
#include "generator/variant_spec.h"

#include <filesystem>
#include <vector>

namespace kdop {

struct Manifest {
    std::vector<VariantSpec> variants;            // in the manifest's order
    std::vector<std::filesystem::path> set_files; // the `set:` files, as the manifest resolves them
};

Result<Manifest> read_manifest(const std::filesystem::path& path);

} // namespace kdop
