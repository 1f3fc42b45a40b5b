// Every chart of variants tells 30 of them apart (issue 59, finding 6: over-time-*.png cycled eight
// colors over twelve variants, so aabb-clip and dop22-clip were the same purple; in trade-*.png
// aabb's circle and dop32's pentagon looked alike): no two series share color and point, or color
// and dash, in the style and in the script gnuplot draws.
#include "harness/chart_style.h"
#include "harness/scratch_directory.h"
#include "harness/subprocess.h"
#include "temporal/taa_chart.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace kdop {
namespace {

// Eight sets (the six built-in ones and two of a user's) in both modes and both neighborhoods, less
// two: 30 variants, and one loop form.
std::vector<VariantKey> thirty_variants() {
    std::vector<VariantKey> keys;
    for (const char* set : {"aabb", "ycocg", "dop16-asphalt", "dop16-grass", "dop22", "dop32", "mine", "yours"})
        for (Mode mode : {Mode::clip, Mode::varclip})
            for (Neighborhood n : {Neighborhood::n9, Neighborhood::n5}) keys.push_back({set, mode, n});
    keys.resize(30);
    keys.push_back(VariantKey{"dop32", Mode::clip, Neighborhood::n9}.with(Form::loop));
    return keys;
}

TEST(ChartStyle, NoTwoOf30VariantsShareColorAndPointOrColorAndDash) {
    const std::vector<VariantKey> keys = thirty_variants();
    const VariantChartStyle style(keys);
    std::set<std::pair<std::string, int>> by_point, by_dash;
    std::set<std::string> colors;
    for (const VariantKey& key : keys) {
        const SeriesLook look = style.look(key);
        EXPECT_TRUE(by_point.insert({look.color, look.point}).second) << key.name();
        EXPECT_TRUE(by_dash.insert({look.color, look.dash}).second) << key.name();
        colors.insert(look.color);
    }
    EXPECT_EQ(colors.size(), 9u) << "a color per set, and one for dop32's loop form";
    // Families past the palette still get colors of their own.
    std::set<std::string> many;
    for (std::size_t i = 0; i < 40; ++i) many.insert(VariantChartStyle::family_color(i));
    EXPECT_EQ(many.size(), 40u);
    EXPECT_EQ(VariantChartStyle::color_value("#1f77b4"), "2062260");
}

// The script gnuplot draws the over-time chart from gives each of the 31 lines the look the style
// gives its variant.
TEST(ChartStyle, TheOverTimeChartDrawsEachVariantInItsOwnLook) {
    if (find_program("gnuplot").empty()) GTEST_SKIP() << "gnuplot is not installed";
    std::vector<TaaFrameRow> rows;
    for (const VariantKey& key : thirty_variants())
        for (std::size_t frame = 0; frame < 3; ++frame)
            rows.push_back({key, "scene", "scene-ghosting", frame, {NAN, 0.01 * double(frame + 1)}});
    ScratchDirectory scratch("kdop-chart-test");
    auto charts = taa_over_time_charts(rows, default_metrics(), scratch.path, scratch.path / "out");
    ASSERT_TRUE(charts) << charts.error().message;
    const std::string script = test::read_file(scratch.path / "charts.gp");
    const std::regex series(R"(with linespoints pt (\d+) ps [0-9.]+ dt (\d+) lw [0-9.]+ lc rgb '(#[0-9a-f]{6})')");
    std::set<std::pair<std::string, std::string>> by_point, by_dash;
    std::size_t lines = 0;
    for (auto it = std::sregex_iterator(script.begin(), script.end(), series); it != std::sregex_iterator(); ++it) {
        ++lines;
        EXPECT_TRUE(by_point.insert({(*it)[3], (*it)[1]}).second) << (*it)[0];
        EXPECT_TRUE(by_dash.insert({(*it)[3], (*it)[2]}).second) << (*it)[0];
    }
    EXPECT_EQ(lines, 31u) << script;
}

} // namespace
} // namespace kdop
