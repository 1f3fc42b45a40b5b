#include "glsl_emitter.h"

#include <fmt/format.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#ifndef KDOP_VERSION
#error "KDOP_VERSION must be defined by the build"
#endif

namespace kdop {
namespace {

constexpr char kComponents[] = "xyz";

// Shortest text that reads back as the same float, always with a '.' or exponent so GLSL sees a
// float literal. Shortest round-trip formatting is exact and platform-independent, which keeps
// generated files byte-identical across machines.
std::string float_literal(float value) {
    std::string s = fmt::format("{}", value);
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

// Shortest text of a double, for comments that quote the axis file's numbers.
std::string number_text(double value) { return fmt::format("{}", value); }

std::string vec3_text(const glm::dvec3& v) {
    return fmt::format("({}, {}, {})", number_text(v.x), number_text(v.y), number_text(v.z));
}

std::string vec3_text(const glm::vec3& v) { return fmt::format("({}, {}, {})", v.x, v.y, v.z); }

std::string upper_identifier(std::string s) {
    for (char& c : s) c = c == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

// The projection of vector expression `v` on a scaled axis, folded: unit components are added or
// subtracted, zero components dropped, and the remaining ones multiplied, by one multiply or one
// dot() over just those components.
std::string project(std::string_view v, const glm::vec3& k) {
    std::string units, negative_units, scaled_components;
    std::vector<float> scales;
    for (int c = 0; c < 3; ++c) {
        if (k[c] == 1.0f)
            units += fmt::format("{}{}.{}", units.empty() ? "" : " + ", v, kComponents[c]);
        else if (k[c] == -1.0f)
            negative_units += fmt::format(" - {}.{}", v, kComponents[c]);
        else if (k[c] != 0.0f) {
            scaled_components += kComponents[c];
            scales.push_back(k[c]);
        }
    }
    std::string scaled;
    // A negative scale stays in the literal: "a - b * k" would cost a negate once fused into an fma.
    if (scales.size() == 1)
        scaled = fmt::format(" + {}.{} * {}", v, scaled_components, float_literal(scales[0]));
    else if (scales.size() == 2)
        scaled = fmt::format(" + dot({}.{}, vec2({}, {}))", v, scaled_components, float_literal(scales[0]),
                             float_literal(scales[1]));
    return units + scaled + negative_units;
}

// min() or max() over q[first, last) as a balanced tree: the same operation count as a chain,
// but a dependency depth of log2(n) instead of n - 1.
std::string reduce_tree(std::string_view op, int first, int last) {
    if (last - first == 1) return fmt::format("q{}", first);
    int middle = first + (last - first) / 2;
    return fmt::format("{}({}, {})", op, reduce_tree(op, first, middle), reduce_tree(op, middle, last));
}

std::string sum(int count, std::string_view term_format) {
    std::string s;
    for (int n = 0; n < count; ++n) s += (n ? " + " : "") + fmt::format(fmt::runtime(term_format), n);
    return s;
}

// Statements shared by both modes: the neighbors' projections q0..qN-1, the current color's p and
// the reciprocal of the ray direction's projection.
void write_projections(std::string& out, const ScaledAxis& axis, int count) {
    for (int n = 0; n < count; ++n)
        out += fmt::format("        float q{} = {};\n", n, project(fmt::format("c{}", n), axis.coefficients));
    out += fmt::format("        float p = {};\n", project("current", axis.coefficients));
    std::string d = project("dir", axis.coefficients);
    bool compound = d.find(' ') != std::string::npos;
    out += fmt::format("        float inv_d = 1.0 / {}{}{};\n", compound ? "(" : "", d, compound ? ")" : "");
}

// Clip: the slab spans the projections' min..max, dilated by the padding. The ray starts inside,
// so only its exit counts: the larger of the two plane crossings. A direction parallel to the slab
// gives inv_d = +-inf and crossings -inf and +inf, so the slab does not limit t.
void write_clip_slab(std::string& out, const ScaledAxis& axis, int count) {
    write_projections(out, axis, count);
    out += fmt::format("        float lo = {} - {};\n", reduce_tree("min", 0, count), float_literal(axis.padding));
    out += fmt::format("        float hi = {} + {};\n", reduce_tree("max", 0, count), float_literal(axis.padding));
    out += "        t = min(t, max((lo - p) * inv_d, (hi - p) * inv_d));\n";
}

// Variance clip (Salvi 2016): the slab spans mean +- gamma * sigma of the projections, widened to
// include the current color so the ray still starts inside.
void write_varclip_slab(std::string& out, const ScaledAxis& axis, int count) {
    write_projections(out, axis, count);
    out += fmt::format("        float mean = ({}) * (1.0 / {}.0);\n", sum(count, "q{}"), count);
    out += fmt::format("        float sigma = sqrt(({}) * (1.0 / {}.0) - mean * mean);\n", sum(count, "q{0} * q{0}"),
                       count);
    out += "        float lo = min(mean - gamma * sigma, p);\n";
    out += "        float hi = max(mean + gamma * sigma, p);\n";
    out += "        t = min(t, max((lo - p) * inv_d, (hi - p) * inv_d));\n";
}

std::string origin_file_name(const AxisSet& set) { return std::filesystem::path(set.origin).filename().string(); }

std::string neighborhood_description(Neighborhood n) {
    return n == Neighborhood::n9 ? "3x3 neighborhood, row-major; index 4 is the pixel itself"
                                 : "plus-shaped neighborhood: up, left, the pixel itself (index 2), right, down";
}

std::string mode_description(Mode m) {
    return m == Mode::clip ? "k-DOP clip (Ikkala et al. 2024): slabs span the neighborhood's min..max"
                           : "k-DOP variance clip (Ikkala et al. 2024, after Salvi 2016): slabs span mean +- gamma * sigma";
}

// Replaces every @KEY@ in `text`; a placeholder without a value is an error naming its line.
Result<std::string> fill_template(std::string_view text, const std::map<std::string, std::string>& values,
                                  std::string_view origin) {
    std::string out;
    size_t pos = 0;
    while (true) {
        size_t open = text.find('@', pos);
        if (open == std::string_view::npos) break;
        size_t close = text.find('@', open + 1);
        int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + open, '\n'));
        if (close == std::string_view::npos)
            return fail(fmt::format("{}:{}: unterminated placeholder (a '@' without its closing '@')", origin, line));
        std::string key(text.substr(open + 1, close - open - 1));
        auto value = values.find(key);
        if (value == values.end()) return fail(fmt::format("{}:{}: unknown placeholder @{}@", origin, line, key));
        out += text.substr(pos, open - pos);
        out += value->second;
        pos = close + 1;
    }
    out += text.substr(pos);
    return out;
}

} // namespace

ScaledAxis scale_axis(const glm::dvec3& axis) {
    int largest = 0;
    for (int c = 1; c < 3; ++c)
        if (std::abs(axis[c]) > std::abs(axis[largest])) largest = c;
    ScaledAxis scaled;
    scaled.factor = 1.0 / axis[largest];
    for (int c = 0; c < 3; ++c) scaled.coefficients[c] = static_cast<float>(axis[c] * scaled.factor) + 0.0f; // -0 -> +0
    scaled.coefficients[largest] = 1.0f;
    scaled.padding = static_cast<float>(kSlabPadding * glm::length(axis) * std::abs(scaled.factor));
    return scaled;
}

std::string glsl_function_name(const VariantSpec& spec) {
    std::string name = "kdop_" + variant_name(spec);
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

std::string regenerate_command(const VariantSpec& spec) {
    // Built-in sets are named; a user's set is its file (by name only, so the text does not depend
    // on where the file sat when it was generated).
    bool builtin = spec.set.origin.starts_with("shader_templates/axis_sets/");
    return fmt::format("kdop gen --sets {} --modes {} --neighborhoods {} --out DIR",
                       builtin ? spec.set.name : origin_file_name(spec.set), to_string(spec.mode),
                       to_string(spec.neighborhood));
}

std::string emit_function(const VariantSpec& spec) {
    const int count = static_cast<int>(neighborhood_offsets(spec.neighborhood).size());
    const int axes = static_cast<int>(spec.set.axes.size());
    const std::string name = glsl_function_name(spec);
    const std::string guard = upper_identifier(name) + "_GLSL";
    const bool varclip = spec.mode == Mode::varclip;

    std::string out;
    out += fmt::format("// {}: {}.\n", variant_name(spec), mode_description(spec.mode));
    out += fmt::format("// Generated by kdop {} (generator/glsl_emitter.cpp) from axis set '{}' ({}):\n", KDOP_VERSION,
                       spec.set.name, origin_file_name(spec.set));
    out += fmt::format("//   {}\n", spec.set.provenance);
    out += fmt::format("// Do not edit; regenerate with `{}`.\n", regenerate_command(spec));
    out += "//\n";
    out += fmt::format("// Returns where the ray from `current` to `history` leaves the {}-DOP ({} slabs) around the\n",
                       2 * axes, axes);
    out += "// neighborhood's colors, or `history` itself when it lies inside. `current` must lie inside\n";
    out += fmt::format("// that k-DOP; normally it is the pixel's own color, neighborhood[{}].\n",
                       neighborhood_center(spec.neighborhood));
    out += fmt::format("// neighborhood[]: {}.\n", neighborhood_description(spec.neighborhood));
    if (varclip) out += "// gamma: slab half-width in standard deviations (1 is the usual choice).\n";
    out += "// Each axis is scaled so that its largest component is +1 (the k-DOP does not change), so a\n";
    out += "// unit component costs no multiply and a zero component nothing.\n";
    if (!varclip) out += "// Slabs are dilated by 1e-5 per unit of axis length, as in the paper.\n";
    out += fmt::format("#ifndef {}\n#define {}\n\n", guard, guard);

    out += fmt::format("vec3 {}(vec3 current, vec3 history, {}vec3 neighborhood[{}])\n{{\n", name,
                       varclip ? "float gamma, " : "", count);
    for (int n = 0; n < count; ++n) out += fmt::format("    vec3 c{} = neighborhood[{}];\n", n, n);
    out += "    vec3 dir = history - current;\n";
    out += "    float t = 1.0; // where current + t * dir leaves the k-DOP; stays 1 while history is inside\n";

    for (int a = 0; a < axes; ++a) {
        const Axis& axis = spec.set.axes[a];
        ScaledAxis scaled = scale_axis(axis.direction);
        out += fmt::format("\n    // Slab {} of {}: axis {} from {}:{}", a + 1, axes, vec3_text(axis.direction),
                           origin_file_name(spec.set), axis.line);
        if (scaled.factor != 1.0)
            out += fmt::format(", scaled by {:.6g} to {}", scaled.factor, vec3_text(scaled.coefficients));
        out += "\n";
        out += "    {\n";
        if (varclip)
            write_varclip_slab(out, scaled, count);
        else
            write_clip_slab(out, scaled, count);
        out += "    }\n";
    }
    out += "\n    return current + max(t, 0.0) * dir;\n}\n\n";
    out += fmt::format("#endif // {}\n", guard);
    return out;
}

Result<std::string> emit_compute_shader(const VariantSpec& spec, std::string_view compute_template,
                                        std::string_view template_origin) {
    auto offsets = neighborhood_offsets(spec.neighborhood);
    std::string gather;
    for (size_t n = 0; n < offsets.size(); ++n)
        gather += fmt::format("        current_at(p + ivec2({:2}, {:2}), last){}\n", offsets[n].x, offsets[n].y,
                              n + 1 < offsets.size() ? "," : "");
    const bool varclip = spec.mode == Mode::varclip;
    std::map<std::string, std::string> values{
        {"VARIANT", variant_name(spec)},
        {"GENERATED_BY", fmt::format("Generated by kdop {} from {} and axis set '{}' ({}).", KDOP_VERSION,
                                     template_origin, spec.set.name, origin_file_name(spec.set))},
        {"REGENERATE", regenerate_command(spec)},
        {"PARAMETERS", varclip ? "layout(push_constant) uniform Parameters\n{\n    float gamma;\n} parameters;\n"
                               : "// Clip variants take no parameters.\n"},
        {"FUNCTION", emit_function(spec)},
        {"NEIGHBOR_COUNT", fmt::format("{}", offsets.size())},
        {"GATHER", gather},
        {"CALL", fmt::format("{}(neighborhood[{}], history, {}neighborhood)", glsl_function_name(spec),
                             neighborhood_center(spec.neighborhood), varclip ? "parameters.gamma, " : "")},
    };
    return fill_template(compute_template, values, template_origin);
}

} // namespace kdop
