// The analytic minimum against hand counts, and every emitted default variant against it: the
// emitted clip must spend exactly the minimum plus its two deliberate constant starts per slab, so
// any operation the emitter or the optimizer adds (or a missed fusion) shows up here.
#include "analytic_cost.h"
#include "spirv_cost.h"
#include "variant_builder.h"

#include <gtest/gtest.h>

namespace kdop {
namespace {

AxisSet set_from(std::string_view text) {
    auto set = parse_axis_set(text, "test.axes");
    EXPECT_TRUE(set) << set.error().message;
    return set ? *set : AxisSet{};
}

TEST(AnalyticCost, MatchesHandCounts) {
    const AxisSet aabb = set_from("name: box\nprovenance: test\n1 0 0\n0 1 0\n0 0 1\n");
    // Per pixel: dir 3, padding scale 6, usable history 9, result 4. Per slab (m = 1, N = 9):
    // extent 16, dilation 2, exit 6.
    EXPECT_EQ(analytic_min_float_ops(aabb, Mode::clip, Neighborhood::n9), 22u + 3 * 24);
    // Per pixel also -gamma, the scaled frame (10) and the 5 colors relative to current (15). Per
    // slab (N = 5): varclip 2*5 + 9 = 19, dilation 2, exit 5.
    EXPECT_EQ(analytic_min_float_ops(aabb, Mode::varclip, Neighborhood::n5), 22u + 26 + 3 * 26);
    // Two nonzero components cost one multiply-add per projection: (9 + 1) * 1 more per such slab;
    // three cost two. The scale of the axis does not matter, only its zeros.
    const AxisSet mixed = set_from("name: mixed\nprovenance: test\n2 0 0\n0 1 -1\n0.2 0.3 0.4\n");
    EXPECT_EQ(analytic_min_float_ops(mixed, Mode::clip, Neighborhood::n9), 22u + 3 * 24 + 10 * 1 + 10 * 2);
}

TEST(AnalyticCost, EmittedDefaultsSpendTheMinimumPlusTheirConstantStarts) {
    auto specs = select_variants({}, {}, {});
    ASSERT_TRUE(specs);
    auto built = build_variants(*specs);
    ASSERT_TRUE(built) << built.error().message;
    for (const BuiltVariant& v : *built) {
        SCOPED_TRACE(v.name);
        const std::size_t minimum = analytic_min_float_ops(v.spec.set, v.spec.mode, v.spec.neighborhood);
        const std::size_t constant_starts = v.spec.mode == Mode::clip ? 2 * v.spec.set.axes.size() : 0;
        EXPECT_EQ(count_float_ops(v.spirv).total(), minimum + constant_starts);
    }
}

} // namespace
} // namespace kdop
