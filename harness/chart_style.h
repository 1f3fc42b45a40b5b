// How every chart of variants tells them apart without labels beside the points (which collide
// where two sets cost the same): a color per family (an axis set, in a form and with numerics), a
// point shape and a dash per mode and neighborhood, and a key of both outside the plot, so it never
// covers a point; and a logarithmic axis where the values span decades, so a few outliers do not
// flatten the rest.
#pragma once

#include "core/variant_key.h"
#include "harness/gnuplot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <span>
#include <string>
#include <vector>

namespace kdop {

// A series' look in a chart: the color of its family, and the point type and dash type of its group.
struct SeriesLook {
    std::string color; // "#rrggbb"
    int point = 7;     // gnuplot's pt
    int dash = 1;      // gnuplot's dt
};

// Families are told apart by color, groups by point shape and dash, so that every variant of 30 (eight
// sets in two modes and two neighborhoods) has a look of its own, in a point chart (color and point) as
// in a line chart (color, dash and point): no two series share both color and point, or color and dash.
class VariantChartStyle {
public:
    // `keys` in the order the key lists their families.
    explicit VariantChartStyle(std::span<const VariantKey> keys);

    // A variant's family: its set, form and numerics ("dop32", "dop32 loop", "dop32 paper"), or its
    // baseline ("gather", "copy").
    static std::string family(const VariantKey& key);
    // A variant's group: its mode and neighborhood ("clip-n9", "varclip-n5", "gather-n9").
    static std::string group(const VariantKey& key);

    SeriesLook look(const VariantKey& key) const;
    // The color of the family's index-th member: ten of Tableau's, then hues spread by the golden
    // angle, each distinct.
    static std::string family_color(std::size_t index);
    // The color as gnuplot's `lc rgb variable` reads it from a data column: 0xrrggbb in decimal.
    static std::string color_value(const std::string& color);

    // The key's entries, for the end of a plot command: each family as a line of its color, each group
    // as its point and dash in black (NaN points and lines, which only the key shows).
    std::string key_entries() const;

private:
    std::vector<std::string> families_, groups_;
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
