#include "harness/chart_style.h"

#include <array>
#include <cmath>

namespace kdop {
namespace {

// Each group's point and dash: a shape of its own (no pentagon beside a circle: the two looked alike
// at chart size), filled for the clip, open for the variance clip.
struct GroupLook {
    Mode mode;
    Neighborhood neighborhood;
    int point, dash;
};
constexpr GroupLook kGroupLooks[] = {
    {Mode::clip, Neighborhood::n9, 7, 1},    {Mode::clip, Neighborhood::n5, 9, 3},
    {Mode::varclip, Neighborhood::n9, 4, 2}, {Mode::varclip, Neighborhood::n5, 12, 4},
    {Mode::gather, Neighborhood::n9, 1, 5},  {Mode::gather, Neighborhood::n5, 2, 5},
    {Mode::copy, Neighborhood::n9, 3, 1},    {Mode::copy, Neighborhood::n5, 3, 1},
    {Mode::shader, Neighborhood::n9, 6, 6},
};

// The group's name in the key: its mode and neighborhood, "no clip" for a shader of its own.
std::string group_name(const GroupLook& g) {
    return g.mode == Mode::shader ? "no clip" : fmt::format("{}-{}", to_string(g.mode), to_string(g.neighborhood));
}

const GroupLook& group_look(const VariantKey& key) {
    if (key.mode == Mode::shader) return kGroupLooks[std::size(kGroupLooks) - 1];
    for (const GroupLook& g : kGroupLooks)
        if (g.mode == key.mode && g.neighborhood == key.neighborhood) return g;
    return kGroupLooks[0];
}

template <class T>
void add_once(std::vector<T>& to, const T& value) {
    if (std::find(to.begin(), to.end(), value) == to.end()) to.push_back(value);
}

} // namespace

VariantChartStyle::VariantChartStyle(std::span<const VariantKey> keys) {
    for (const VariantKey& key : keys) {
        add_once(families_, family(key));
        add_once(groups_, group(key));
    }
}

std::string VariantChartStyle::family(const VariantKey& key) {
    if (key.mode == Mode::shader) return key.set;
    if (!key.is_clip()) return to_string(key.mode);
    std::string name = key.set;
    if (key.form == Form::loop) name += " loop";
    if (key.numerics == Numerics::paper) name += " paper";
    return name;
}

std::string VariantChartStyle::group(const VariantKey& key) {
    if (key.mode == Mode::shader) return "no clip";
    return fmt::format("{}-{}", to_string(key.mode), to_string(key.neighborhood));
}

std::string VariantChartStyle::family_color(std::size_t index) {
    // Tableau 10: hues far apart that stay apart for the common forms of color blindness.
    static constexpr std::array<const char*, 10> tableau = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                            "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
    if (index < tableau.size()) return tableau[index];
    // Past them, hues spread by the golden angle (each new one far from the last), at two
    // brightnesses in turn.
    const double hue = std::fmod(double(index - tableau.size()) * 137.50776405, 360.0) / 60.0;
    const double value = index % 2 ? 0.55 : 0.8, saturation = 0.7, chroma = value * saturation;
    const double x = chroma * (1 - std::fabs(std::fmod(hue, 2.0) - 1)), m = value - chroma;
    const int sector = int(hue) % 6;
    const double rgb[6][3] = {{chroma, x, 0}, {x, chroma, 0}, {0, chroma, x},
                              {0, x, chroma}, {x, 0, chroma}, {chroma, 0, x}};
    auto byte = [&](double c) { return int(std::lround((c + m) * 255)); };
    return fmt::format("#{:02x}{:02x}{:02x}", byte(rgb[sector][0]), byte(rgb[sector][1]), byte(rgb[sector][2]));
}

std::string VariantChartStyle::color_value(const std::string& color) {
    return std::to_string(std::stoul(color.substr(1), nullptr, 16));
}

SeriesLook VariantChartStyle::look(const VariantKey& key) const {
    const auto at = std::find(families_.begin(), families_.end(), family(key)) - families_.begin();
    const GroupLook& g = group_look(key);
    return {family_color(std::size_t(at)), g.point, g.dash};
}

std::string VariantChartStyle::key_entries() const {
    std::string out;
    for (std::size_t f = 0; f < families_.size(); ++f)
        out += fmt::format(", NaN with lines lw 4 lc rgb '{}' title {}", family_color(f), gnuplot_string(families_[f]));
    for (const std::string& group : groups_)
        for (const GroupLook& g : kGroupLooks)
            if (group_name(g) == group)
                out += fmt::format(", NaN with linespoints pt {} ps 1.5 dt {} lw 1.5 lc rgb 'black' title {}", g.point,
                                   g.dash, gnuplot_string(group));
    return out;
}

} // namespace kdop
