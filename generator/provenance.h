// What every generated file says about itself: where it came from (kdop's version, the axis set and
// its file) and the command that regenerates it.
#pragma once

#include "generator/axis_set.h"
#include "generator/shader_dialect.h"
#include "generator/variant_spec.h"

#include <string>

namespace kdop {

// The axis set's file name, without its folder (the text must not depend on where the file sat),
// safe inside a line comment.
std::string axis_file_name(const AxisSet& set);

// What a mode computes, in a phrase: "k-DOP clip (Ikkala et al. 2024): slabs span ...".
std::string mode_description(Mode m);

// The command that regenerates a variant, quoted in generated headers.
std::string regenerate_command(const VariantSpec& spec);

// The comment block above a variant's clip function: what it computes, from what, the contract on
// its arguments and its numerics.
std::string function_header(const VariantSpec& spec, const Dialect& dialect);

} // namespace kdop
