#include "generator/clip_emitter.h"

#include "generator/analytic_cost.h"
#include "generator/provenance.h"
#include "generator/scaled_axis.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

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
// subtracted, zero components dropped, and the remaining ones multiplied: one multiply-add each
// (multiply_add), one dot() over just those components (fold_dot), or one dot() over every nonzero
// component including the unit one (full_dot).
std::string project(std::string_view v, const glm::vec3& k, EmitStyle::Projection style, const Dialect& dialect) {
    if (style == EmitStyle::Projection::full_dot) {
        std::string components;
        std::vector<std::string> values;
        for (int c = 0; c < 3; ++c)
            if (k[c] != 0.0f) {
                components += kComponents[c];
                values.push_back(float_literal(k[c]));
            }
        if (values.size() == 1) return fmt::format("{}.{}", v, components); // the unit component itself
        std::string operand = components == "xyz" ? std::string(v) : fmt::format("{}.{}", v, components);
        return fmt::format("dot({}, {}({}))", operand, dialect.vec(static_cast<int>(values.size())),
                           fmt::join(values, ", "));
    }
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
    if (scales.size() == 2 && style == EmitStyle::Projection::multiply_add &&
        std::abs(scales[0]) == std::abs(scales[1])) {
        // Two components with one scale (YCoCg's Y and Cg): their sum or difference is scaled once.
        // The same float-op count as two multiply-adds, but one multiply less on a device without
        // fused multiply-add (lavapipe splits every Fma into a multiply and an add).
        scaled = fmt::format(" + ({0}.{1} {3} {0}.{2}) * {4}", v, scaled_components[0], scaled_components[1],
                             scales[0] == scales[1] ? '+' : '-', float_literal(scales[0]));
    } else if (scales.size() == 1 || (scales.size() == 2 && style == EmitStyle::Projection::multiply_add)) {
        for (std::size_t i = 0; i < scales.size(); ++i)
            scaled += fmt::format(" + {}.{} * {}", v, scaled_components[i], float_literal(scales[i]));
    } else if (scales.size() == 2)
        scaled = fmt::format(" + dot({}.{}, {}({}, {}))", v, scaled_components, dialect.vec(2),
                             float_literal(scales[0]), float_literal(scales[1]));
    return units + scaled + negative_units;
}

// min() or max() over the projections q<n> of neighbors[first, last) as a balanced tree: the same
// operation count as a chain, but a dependency depth of log2(n) instead of n - 1.
std::string reduce_tree(std::string_view op, const std::vector<int>& neighbors, int first, int last) {
    if (last - first == 1) return fmt::format("q{}", neighbors[first]);
    int middle = first + (last - first) / 2;
    return fmt::format("{}({}, {})", op, reduce_tree(op, neighbors, first, middle),
                       reduce_tree(op, neighbors, middle, last));
}

std::string reciprocal(const std::string& expression) {
    bool compound = expression.find(' ') != std::string::npos;
    return compound ? fmt::format("1.0 / ({})", expression) : fmt::format("1.0 / {}", expression);
}

std::string sum(int count, std::string_view term_format) {
    std::string s;
    for (int n = 0; n < count; ++n) s += (n ? " + " : "") + fmt::format(fmt::runtime(term_format), n);
    return s;
}

// The ray starts inside the slab, so it leaves through the plane it heads for: hi where its
// projection grows, lo where it shrinks. Choosing by the sign of inv_d rather than of d keeps a ray
// parallel to the slab (d = +-0, inv_d = +-inf) from stopping at it: the chosen plane's distance
// then has inv_d's sign and the exit is +inf. A compare and a select cost one float op less than
// computing both crossings and taking the larger. (The paper's numerics.)
std::string paper_exit_update(const Dialect& dialect) {
    return fmt::format("        t = min(t, (({}) - p) * inv_d);\n", dialect.select("inv_d > 0.0", "hi", "lo"));
}

// Hardened, lo and hi are relative to the ray's origin, which they contain, and padded after:
// lo <= -padding < 0 < padding <= hi, however float rounds. The plane the ray heads for is chosen by d's sign bit,
// which tells -0 from +0: a parallel ray (d = +-0) divides a distance of the same sign by it and
// gets +inf, never 0 / 0; and every exit is positive, so t stays in (0, 1]. One division instead
// of a reciprocal and a multiply.
std::string hardened_exit(const Dialect& dialect) {
    return fmt::format("        t = min(t, ({}) / d);\n",
                       dialect.select(fmt::format("{}(d) < 0", dialect.float_bits_to_int), "lo", "hi"));
}

// The paper's slab dilation, 1e-5 per unit of axis length, on both sides.
std::string dilation(const ScaledAxis& axis) {
    return fmt::format("        lo -= {0};\n        hi += {0};\n", float_literal(axis.padding));
}

// `float <name> = ...;`: the min() or max() (`op`) of `start` (if any) and the projections q<n> of
// `neighbors`, updated neighbor by neighbor from `start`, or as a balanced tree joined with it.
void write_extent(std::string& out, std::string_view name, std::string_view op, std::string_view start,
                  const std::vector<int>& neighbors, EmitStyle::Extent extent, const Dialect& dialect) {
    const std::string declaration = dialect.declare("float", name, true); // padded or moved after
    if (extent == EmitStyle::Extent::running) {
        out += fmt::format("        {} = {};\n", declaration, start);
        for (int n : neighbors) out += fmt::format("        {0} = {1}({0}, q{2});\n", name, op, n);
        return;
    }
    const std::string tree = reduce_tree(op, neighbors, 0, static_cast<int>(neighbors.size()));
    out += start.empty() ? fmt::format("        {} = {};\n", declaration, tree)
                         : fmt::format("        {} = {}({}, {});\n", declaration, op, tree, start);
}

// Clip: the slab spans the projections' min..max.
// With the paper's numerics that is every neighbor's projection, dilated by the padding, and the
// exit is measured from the current color's projection p.
// Hardened, the same slab in coordinates relative to the ray's origin, padded only then, so that
// neither float rounding (p - padding is p above ~84) nor a flat neighborhood can put the origin on
// a plane. `current` stands for the center pixel, whose projection is the origin. In the relative
// frame the colors already are relative to current (write_unrolled_body), so the extents start from
// 0, the center; in the absolute frame p is subtracted once per slab and the center joined after.
// Starting the running extents from constants rather than from the first projection measured 8%
// fewer lavapipe instructions per pixel for dop32 (the driver can drop its NaN handling down the
// chain once a constant operand makes the result non-NaN); a NaN neighbor also drops out instead of
// poisoning the extent.
void write_clip_slab(std::string& out, const ScaledAxis& axis, const std::vector<int>& neighbors,
                     const EmitStyle& style, Numerics numerics, Frame frame, const Dialect& dialect) {
    auto proj = [&](std::string_view v) { return project(v, axis.coefficients, style.projection, dialect); };
    for (int n : neighbors)
        out += fmt::format("        {} = {};\n", dialect.declare("float", fmt::format("q{}", n)),
                           proj(fmt::format("c{}", n)));
    const std::string padding = float_literal(axis.padding);
    const bool running = style.extent == EmitStyle::Extent::running;
    const std::string largest(running ? dialect.float_max : ""), lowest(running ? "-" + largest : "");
    const std::string p = dialect.declare("float", "p");
    if (numerics == Numerics::paper) {
        write_extent(out, "lo", "min", largest, neighbors, style.extent, dialect);
        write_extent(out, "hi", "max", lowest, neighbors, style.extent, dialect);
        out += dilation(axis);
        out += fmt::format("        {} = {};\n", p, proj("current"));
        out += fmt::format("        {} = {};\n", dialect.declare("float", "inv_d"), reciprocal(proj("dir")));
        out += paper_exit_update(dialect);
        return;
    }
    if (frame == Frame::relative) {
        write_extent(out, "lo", "min", "0.0", neighbors, style.extent, dialect);
        write_extent(out, "hi", "max", "0.0", neighbors, style.extent, dialect);
        out += dilation(axis);
    } else {
        write_extent(out, "lo", "min", largest, neighbors, style.extent, dialect);
        write_extent(out, "hi", "max", lowest, neighbors, style.extent, dialect);
        out += fmt::format("        {} = {};\n", p, proj("current"));
        out += fmt::format("        lo = min(lo - p, 0.0) - {};\n", padding);
        out += fmt::format("        hi = max(hi - p, 0.0) + {};\n", padding);
    }
    out += fmt::format("        {} = {};\n", dialect.declare("float", "d"), proj("dir"));
    out += hardened_exit(dialect);
}

// Variance clip (Salvi 2016): the slab spans mean +- gamma * sigma of the projections.
// With the paper's numerics it is widened to include the current color's projection p, so the ray
// starts inside, and dilated by the padding.
// Hardened, the colors and the ray arrive relative to current and scaled (see
// write_hardening_prologue), so the projections are relative to the ray's origin; as in the clip,
// `current` stands for the center pixel (projection 0, so it adds nothing to the sums), and the slab
// is widened to contain the origin, then padded. The shift keeps float32 from cancelling
// the small variance of bright, flat areas away: the supplement's E[q^2] - E[q]^2 gives a sigma of
// about 3e-4 |q| there, or a negative variance and NaN.
void write_varclip_slab(std::string& out, const ScaledAxis& axis, const std::vector<int>& neighbors, int count,
                        const EmitStyle& style, Numerics numerics, const Dialect& dialect) {
    auto proj = [&](std::string_view v) { return project(v, axis.coefficients, style.projection, dialect); };
    const bool hardened = numerics == Numerics::hardened;
    auto let = [&](std::string_view name) { return dialect.declare("float", name); };
    if (!hardened) out += fmt::format("        {} = {};\n", let("p"), proj("current"));
    for (int n : neighbors)
        out += fmt::format("        {} = {};\n", let(fmt::format("q{}", n)), proj(fmt::format("c{}", n)));
    std::string sum, squares;
    for (int n : neighbors) {
        sum += fmt::format("{}q{}", sum.empty() ? "" : " + ", n);
        squares += fmt::format("{0}q{1} * q{1}", squares.empty() ? "" : " + ", n);
    }
    out += fmt::format("        {} = {};\n", let("sum"), sum);
    out += fmt::format("        {} = sum * (1.0 / {}.0);\n", let("mean"), count);
    if (hardened) {
        // Written so every multiply-add fuses without a negation: the variance is
        // (sum q^2 - sum q * mean) / N, and -gamma is shared by all slabs.
        out += fmt::format("        {3} = {2}(sum, sum * (-1.0 / {0}.0), {1}) * (1.0 / {0}.0);\n", count, squares,
                           dialect.fma, let("variance"));
        out += fmt::format("        {} = sqrt(max(variance, 0.0));\n", let("sigma"));
        out += fmt::format("        {} = min({}(-gamma, sigma, mean), 0.0);\n", dialect.declare("float", "lo", true),
                           dialect.fma);
        out += fmt::format("        {} = max({}(gamma, sigma, mean), 0.0);\n", dialect.declare("float", "hi", true),
                           dialect.fma);
        out += fmt::format("        lo = {1}(scale, -{0}, lo);\n        hi = {1}(scale, {0}, hi);\n",
                           float_literal(axis.padding), dialect.fma);
        out += fmt::format("        {} = {};\n", let("d"), proj("ray"));
        out += hardened_exit(dialect);
        return;
    }
    out += fmt::format("        {} = sqrt(({}) * (1.0 / {}.0) - mean * mean);\n", let("sigma"), squares, count);
    out += fmt::format("        {} = min({}(-gamma, sigma, mean), p);\n", dialect.declare("float", "lo", true),
                       dialect.fma);
    out += fmt::format("        {} = max({}(gamma, sigma, mean), p);\n", dialect.declare("float", "hi", true),
                       dialect.fma);
    out += dilation(axis);
    out += fmt::format("        {} = {};\n", let("inv_d"), reciprocal(proj("dir")));
    out += paper_exit_update(dialect);
}

std::string signature(const VariantSpec& spec, const Dialect& dialect) {
    if (dialect.wgsl())
        return fmt::format("fn {}(current: vec3f, history: vec3f, {}neighborhood: array<vec3f, {}>) -> vec3f",
                           glsl_function_name(spec), spec.mode == Mode::varclip ? "gamma: f32, " : "",
                           neighborhood_offsets(spec.neighborhood).size());
    return fmt::format("{0} {1}({0} current, {0} history, {2}{0} neighborhood[{3}])", dialect.vec(3),
                       glsl_function_name(spec), spec.mode == Mode::varclip ? "float gamma, " : "",
                       neighborhood_offsets(spec.neighborhood).size());
}

// Hardened numerics, shared by both forms: whether the history can be used. A history with a NaN or
// Inf channel, or so far out that a projection of the ray could overflow, is replaced by current;
// the sum below is then NaN or above FLT_MAX, and the compare is false for NaN. Below that bound no
// projection of current or of the ray overflows: each is at most the vector's channel magnitudes
// summed, as no scaled or unit axis component exceeds 1.
// Variance clip also gets `scale`, a power of two that brings colors relative to current into a
// range whose squares neither overflow nor underflow: 1, or 2^-100 once the pixel exceeds 2^60.
// A power of two scales exactly, so fma(c, scale, -current * scale) is (c - current) * scale
// rounded once, as the plain difference would be.
void write_hardening_prologue(std::string& out, Mode mode, const Dialect& dialect) {
    out += "    // A history with NaN or Inf, or too far out to project without overflow, is not used.\n";
    out += fmt::format("    {} = abs(current);\n", dialect.declare("vec3", "current_size"));
    out += fmt::format("    {} = abs(dir) + current_size;\n", dialect.declare("vec3", "reach"));
    out += fmt::format("    {} = reach.x + reach.y + reach.z <= {};\n", dialect.declare("bool", "history_usable"),
                       dialect.float_max);
    if (mode != Mode::varclip) return;
    out += "    // Moments of colors relative to current, scaled so squares of HDR differences stay finite.\n";
    const std::string threshold = float_literal(std::ldexp(1.0f, 60)), small = float_literal(std::ldexp(1.0f, -100));
    out += fmt::format("    {} = max(max(current_size.x, current_size.y), current_size.z) > {}; // 2^60\n",
                       dialect.declare("bool", "huge"), threshold);
    out += fmt::format("    {} = {}; // 2^-100\n", dialect.declare("float", "scale"),
                       dialect.select("huge", small, "1.0"));
    out += fmt::format("    {} = current * ({});\n", dialect.declare("vec3", "origin"),
                       dialect.select("huge", "-" + small, "-1.0"));
    out += fmt::format("    {} = dir * scale;\n", dialect.declare("vec3", "ray"));
}

// The neighbors a slab reads: all of them with the paper's numerics; hardened, all but the center,
// for which `current` stands (its projection is the ray's origin, or 0 relative to it).
std::vector<int> slab_neighbors(const VariantSpec& spec) {
    const int count = static_cast<int>(neighborhood_offsets(spec.neighborhood).size());
    std::vector<int> neighbors;
    for (int n = 0; n < count; ++n)
        if (spec.numerics == Numerics::paper || n != neighborhood_center(spec.neighborhood)) neighbors.push_back(n);
    return neighbors;
}

void write_unrolled_body(std::string& out, const VariantSpec& spec, const Dialect& dialect) {
    const int count = static_cast<int>(neighborhood_offsets(spec.neighborhood).size());
    const int axes = static_cast<int>(spec.set.axes.size());
    const bool hardened = spec.numerics == Numerics::hardened;
    const Frame frame = hardened ? hardened_frame(spec.set, spec.mode, spec.neighborhood) : Frame::absolute;
    const std::vector<int> neighbors = slab_neighbors(spec);
    const std::string vec3 = dialect.vec(3);
    out += fmt::format("    {} = history - current;\n", dialect.declare("vec3", "dir"));
    if (hardened) write_hardening_prologue(out, spec.mode, dialect);
    for (int n : neighbors) {
        const std::string c = dialect.declare("vec3", fmt::format("c{}", n));
        if (frame == Frame::absolute)
            out += fmt::format("    {} = neighborhood[{}];\n", c, n);
        else if (spec.mode == Mode::varclip)
            out += fmt::format("    {} = {}(neighborhood[{}], {}, origin);\n", c, dialect.fma, n,
                               dialect.splat(3, "scale"));
        else
            out += fmt::format("    {} = neighborhood[{}] - current;\n", c, n);
    }
    out += fmt::format("    {} = 1.0; // where current + t * dir leaves the k-DOP; stays 1 while history is inside\n",
                       dialect.declare("float", "t", true));
    for (int a = 0; a < axes; ++a) {
        const Axis& axis = spec.set.axes[a];
        ScaledAxis scaled = scale_axis(axis.direction);
        out += fmt::format("\n    // Slab {} of {}: axis {} from {}:{}", a + 1, axes, vec3_text(axis.direction),
                           axis_file_name(spec.set), axis.line);
        if (scaled.factor != 1.0)
            out += std::isfinite(scaled.factor)
                       ? fmt::format(", scaled by {:.6g} to {}", scaled.factor, vec3_text(scaled.coefficients))
                       : fmt::format(", scaled to {}", vec3_text(scaled.coefficients));
        out += "\n    {\n";
        if (spec.mode == Mode::varclip)
            write_varclip_slab(out, scaled, neighbors, count, spec.style, spec.numerics, dialect);
        else
            write_clip_slab(out, scaled, neighbors, spec.style, spec.numerics, frame, dialect);
        out += "    }\n";
    }
    // current + t * dir, written as fma because spirv-opt fuses only scalar multiply-adds.
    out += "\n";
    if (hardened)
        out += fmt::format("    return {}; // 0 < t <= 1\n",
                           dialect.select("history_usable",
                                          fmt::format("{}({}, dir, current)", dialect.fma, dialect.splat(3, "t")),
                                          "current"));
    else
        out += fmt::format("    return {}({}, dir, current);\n", dialect.fma, dialect.splat(3, "max(t, 0.0)"));
}

// `for (int i = 0; i < count; ++i)` with the dialect's unroll attribute, or WGSL's `for (var i = 0; ...; i++)`.
std::string counted_loop(const Dialect& dialect, std::string_view i, int count) {
    return dialect.wgsl() ? fmt::format("for (var {0} = 0; {0} < {1}; {0}++)", i, count)
                          : fmt::format("{0}for (int {1} = 0; {1} < {2}; ++{1})", dialect.unroll, i, count);
}

// The hardened function in the loop form, relative to current as the unrolled form's relative frame
// is (the axes at unit length, so the padding is epsilon itself).
void write_hardened_loop(std::string& out, Mode mode, int count, int center, int axes, const Dialect& dialect) {
    const std::string vec2 = dialect.vec(2);
    auto let = [&](std::string_view type, std::string_view name) { return dialect.declare(type, name); };
    auto var = [&](std::string_view type, std::string_view name) { return dialect.declare(type, name, true); };
    write_hardening_prologue(out, mode, dialect);
    out += fmt::format("    {} = 1.0;\n", var("float", "t"));
    out += fmt::format("    {}\n    {{\n", counted_loop(dialect, "a", axes));
    out += fmt::format("        {} = axes[a];\n", let("vec3", "axis"));
    if (mode == Mode::clip) {
        out += fmt::format("        {} = {}; // current, for neighborhood[{}], at the origin\n", var("vec2", "extent"),
                           dialect.splat(2, "0.0"), center);
        out += fmt::format("        {}\n        {{\n", counted_loop(dialect, "n", count));
        // A guarded body rather than `continue`, which keeps spirv-opt from unrolling the loop.
        out += fmt::format("            if (n != {})\n            {{\n", center);
        out += fmt::format("                {} = dot(neighborhood[n] - current, axis);\n", let("float", "q"));
        out += fmt::format("                extent = {}(min(q, extent.x), max(q, extent.y));\n", vec2);
        out += "            }\n";
        out += "        }\n";
        out += fmt::format("        extent += {}(-epsilon, epsilon);\n", vec2);
        out += fmt::format("        {} = dot(dir, axis);\n", let("float", "d"));
    } else {
        out += fmt::format("        {} = {};\n", var("vec2", "moments"), dialect.splat(2, "0.0"));
        out += fmt::format("        {}\n        {{\n", counted_loop(dialect, "n", count));
        out += fmt::format("            if (n != {}) // current stands for it: 0 relative to itself\n            {{\n",
                           center);
        out += fmt::format("                {} = dot({}(neighborhood[n], {}, origin), axis);\n", let("float", "q"),
                           dialect.fma, dialect.splat(3, "scale"));
        out += fmt::format("                moments += {}(q, q * q);\n", vec2);
        out += "            }\n";
        out += "        }\n";
        out += fmt::format("        moments /= {};\n", dialect.splat(2, fmt::format("{}.0", count)));
        out += fmt::format("        {} = sqrt(max(moments.y - moments.x * moments.x, 0.0));\n", let("float", "sigma"));
        out +=
            fmt::format("        {} = {}(min(moments.x - gamma * sigma, 0.0), max(moments.x + gamma * sigma, 0.0));\n",
                        var("vec2", "extent"), vec2);
        out += fmt::format("        extent += {}(-epsilon, epsilon) * scale;\n", vec2);
        out += fmt::format("        {} = dot(ray, axis);\n", let("float", "d"));
    }
    out += fmt::format("        t = min(t, ({}) / d);\n",
                       dialect.select(fmt::format("{}(d) < 0", dialect.float_bits_to_int), "extent.x", "extent.y"));
    out += "    }\n";
    out += fmt::format("    return {};\n", dialect.select("history_usable", "current + t * dir", "current"));
}

// The supplement's listing: the axes at unit length (as the supplement lists them; a user's file
// need not), in a constant array; loops over axes and neighbors; entry and exit bounds. With paper
// numerics it is the listing itself (the epsilon intent fixed); hardened, it computes the same
// function as the hardened unrolled form, in the listing's loops.
void write_loop_body(std::string& out, const VariantSpec& spec, const Dialect& dialect) {
    const int count = static_cast<int>(neighborhood_offsets(spec.neighborhood).size());
    const int axes = static_cast<int>(spec.set.axes.size());
    const std::string vec2 = dialect.vec(2), vec3 = dialect.vec(3);
    auto let = [&](std::string_view type, std::string_view name) { return dialect.declare(type, name); };
    auto var = [&](std::string_view type, std::string_view name) { return dialect.declare(type, name, true); };
    out += dialect.wgsl() ? fmt::format("    const axes = {}\n", dialect.array_open(3, axes))
                          : fmt::format("    const {} axes[{}] = {}\n", vec3, axes, dialect.array_open(3, axes));
    for (int a = 0; a < axes; ++a) {
        const glm::vec3 v(unit_direction(spec.set.axes[a].direction));
        out += fmt::format("        {}({}, {}, {}){}\n", vec3, float_literal(v.x), float_literal(v.y),
                           float_literal(v.z), a + 1 < axes ? "," : "");
    }
    out += fmt::format("    {};\n", dialect.array_close());
    out += dialect.wgsl() ? "    const epsilon: f32 = 1e-5;\n" : "    const float epsilon = 1e-5;\n";
    out += fmt::format("    {} = history - current;\n", let("vec3", "dir"));
    if (spec.numerics == Numerics::hardened) {
        write_hardened_loop(out, spec.mode, count, neighborhood_center(spec.neighborhood), axes, dialect);
        return;
    }
    out +=
        dialect.wgsl() ? "    var near: f32 = -1e9;\n    var far: f32 = 1e9;\n" : "    float near = -1e9, far = 1e9;\n";
    out += fmt::format("    {}\n    {{\n", counted_loop(dialect, "a", axes));
    out += fmt::format("        {} = axes[a];\n", let("vec3", "axis"));
    out += fmt::format("        {} = dot(current, axis);\n", let("float", "proj_pos"));
    out += fmt::format("        {} = 1.0 / dot(dir, axis);\n", let("float", "inv_dir"));
    out += spec.mode == Mode::clip ? fmt::format("        {} = {}(1e9, -1e9);\n", var("vec2", "extent"), vec2)
                                   : fmt::format("        {} = {};\n", var("vec2", "moments"), dialect.splat(2, "0.0"));
    out += fmt::format("        {}\n        {{\n", counted_loop(dialect, "n", count));
    out += fmt::format("            {} = dot(neighborhood[n], axis);\n", let("float", "t"));
    if (spec.mode == Mode::clip) {
        out += "            extent.x = min(t, extent.x);\n";
        out += "            extent.y = max(t, extent.y);\n";
        out += "        }\n";
    } else {
        out += fmt::format("            moments += {}(t, t * t);\n", vec2);
        out += "        }\n";
        out += fmt::format("        moments /= {};\n", dialect.splat(2, fmt::format("{}.0", count)));
        out += fmt::format("        {} = sqrt(moments.y - moments.x * moments.x);\n", let("float", "sigma"));
        out += fmt::format("        {} = {}(min(moments.x - gamma * sigma, proj_pos), max(moments.x + gamma * "
                           "sigma, proj_pos));\n",
                           var("vec2", "extent"), vec2);
    }
    out += fmt::format("        extent += {}(-epsilon, epsilon) * length(axis);\n", vec2);
    out += fmt::format("        {} = (extent.x - proj_pos) * inv_dir;\n", let("float", "t0"));
    out += fmt::format("        {} = (extent.y - proj_pos) * inv_dir;\n", let("float", "t1"));
    out += "        near = max(near, min(t0, t1));\n";
    out += "        far = min(far, max(t0, t1));\n";
    out += "    }\n";
    out += "    if (near <= far && (near > 0.0 || far > 0.0))\n    {\n";
    out += fmt::format("        {} = clamp({}, 0.0, 1.0);\n", let("float", "t"),
                       dialect.select("near > 0.0", "near", "far"));
    out += "        return current + t * dir;\n";
    out += "    }\n";
    out += "    return current;\n";
}

std::string emit_baseline_function(const VariantSpec& spec, const Dialect& dialect) {
    const int count = static_cast<int>(neighborhood_offsets(spec.neighborhood).size());
    std::string out = fmt::format("// {}: {}.\n", variant_name(spec), mode_description(spec.mode));
    out += fmt::format("// Generated by kdop {} (generator/clip_emitter.cpp). A cost baseline, not a clip.\n",
                       KDOP_VERSION);
    out += fmt::format("{}\n{{\n", signature(spec, dialect));
    if (spec.mode == Mode::copy) {
        out += "    return history;\n";
    } else {
        out += "    // Every input is used once, so no load is optimized away.\n";
        out += fmt::format("    return history + {};\n", sum(count, "neighborhood[{}]"));
    }
    return out + "}\n";
}

} // namespace

std::string glsl_function_name(const VariantSpec& spec) {
    std::string name = "kdop_" + variant_name(spec);
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

std::string emit_function(const VariantSpec& spec, const Dialect& dialect) {
    if (spec.mode == Mode::gather || spec.mode == Mode::copy) return emit_baseline_function(spec, dialect);
    const std::string guard = upper_identifier(glsl_function_name(spec)) + "_" + std::string(dialect.language);
    std::string out = function_header(spec, dialect);
    // WGSL has no preprocessor, so no include guard: a module pastes the function in once.
    if (!dialect.wgsl()) out += fmt::format("#ifndef {}\n#define {}\n", guard, guard);
    if (spec.form == Form::loop) out += dialect.loop_extension;
    out += "\n" + signature(spec, dialect) + "\n{\n";
    if (spec.form == Form::loop)
        write_loop_body(out, spec, dialect);
    else
        write_unrolled_body(out, spec, dialect);
    out += "}\n";
    if (!dialect.wgsl()) out += fmt::format("\n#endif // {}\n", guard);
    return out;
}

} // namespace kdop
