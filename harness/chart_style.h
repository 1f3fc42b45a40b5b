// How every chart of variants tells them apart without labels beside the points (which collide
// where two sets cost the same): a color per mode and neighborhood, a point shape per axis set, and
// a key of both outside the plot, so it never covers a point; and a logarithmic axis where the
// values span decades, so a few outliers do not flatten the rest.
#pragma once

#include "core/variant_key.h"
#include "harness/gnuplot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <span>
#include <string>
#include <vector>

namespace kdop {

class VariantChartStyle {
public:
    // `sets` in the order the key lists them.
    explicit VariantChartStyle(std::vector<std::string> sets) : sets_(std::move(sets)) {}

    // The groups of the key, each a mode and a neighborhood: "clip-n9", ...
    static std::string group(const VariantKey& key) {
        return fmt::format("{}-{}", to_string(key.mode), to_string(key.neighborhood));
    }
    static const char* color(const VariantKey& key) {
        static constexpr const char* colors[] = {"#7b2fbe", "#2b9fd9", "#e0a800", "#d62d20"}; // clip n9, n5; varclip
        const int index = (key.mode == Mode::varclip ? 2 : 0) + (key.neighborhood == Neighborhood::n5 ? 1 : 0);
        return colors[index];
    }
    // gnuplot's point type for the key's set: filled shapes first, then open ones, in turn.
    int shape(const std::string& set) const {
        static constexpr int shapes[] = {7, 5, 9, 11, 13, 15, 6, 4, 8, 10, 12, 14};
        const auto at = std::find(sets_.begin(), sets_.end(), set) - sets_.begin();
        return shapes[std::size_t(at) % std::size(shapes)];
    }
    // The key's entries, for the end of a plot command: each group drawn in its color, each set in
    // its shape (NaN points, which only the key shows).
    std::string key_entries(std::span<const VariantKey> keys) const {
        std::vector<std::string> groups;
        std::string out;
        for (const VariantKey& k : keys)
            if (std::find(groups.begin(), groups.end(), group(k)) == groups.end()) {
                groups.push_back(group(k));
                out += fmt::format(", NaN with points pt 7 ps 1.5 lc rgb '{}' title {}", color(k),
                                   gnuplot_string(group(k)));
            }
        for (const std::string& set : sets_)
            out +=
                fmt::format(", NaN with points pt {} ps 1.5 lc rgb 'black' title {}", shape(set), gnuplot_string(set));
        return out;
    }

private:
    std::vector<std::string> sets_;
};

// "set logscale <axis>" where `values` (the finite ones) are all positive and span more than a
// factor of 30, else a linear axis, from 0 or (`from_zero` false, for a scatter of close values)
// around the values; `label` gains " (log scale)" with the former.
inline std::string axis_scale(char axis, std::span<const double> values, const std::string& label,
                              bool from_zero = true) {
    double low = INFINITY, high = 0;
    for (double v : values)
        if (std::isfinite(v)) {
            low = std::min(low, v);
            high = std::max(high, v);
        }
    if (low > 0 && high / low > 30)
        return fmt::format("set logscale {0}\nset {0}range [*:*]\nset {0}label {1}\n", axis,
                           gnuplot_string(label + " (log scale)"));
    return fmt::format("unset logscale {0}\nset {0}range [{2}:*]\nset {0}label {1}\n", axis, gnuplot_string(label),
                       from_zero ? "0" : "*");
}

} // namespace kdop
