// The analytic bound against hand counts, and every emitted default variant against it: the
// emitted clip must spend exactly its frame's count plus, in the absolute frame, its two deliberate
// constant starts per slab, and no frame may beat the bound; so any operation the emitter or the
// optimizer adds (or a missed fusion) shows up here.
#include "generator/analytic_cost.h"

#include "generator/spirv_cost.h"
#include "generator/variant_builder.h"

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
    // Per pixel 18. Per slab (m = 1, N = 9), absolute: extent 2 * 7, minus p 2, joined with the
    // origin 2, padding 2, exit 3; relative: 24 per pixel more, extent 2 * 8, padding 2, exit 3 per
    // slab. Absolute is the cheaper.
    EXPECT_EQ(frame_float_ops(aabb, Mode::clip, Neighborhood::n9, false), 18u + 3 * 23);
    EXPECT_EQ(frame_float_ops(aabb, Mode::clip, Neighborhood::n9, true), 18u + 24 + 3 * 21);
    EXPECT_EQ(analytic_min_float_ops(aabb, Mode::clip, Neighborhood::n9), 18u + 3 * 23);
    // Varclip (N = 5): per pixel 18 + 12 + 11, per slab 2 * 5 + 11.
    EXPECT_EQ(analytic_min_float_ops(aabb, Mode::varclip, Neighborhood::n5), 41u + 3 * 21);
    // Two nonzero components cost one multiply-add per projection, three cost two: relative, N per
    // slab (the 8 neighbors and the ray). The scale of the axis does not matter, only its zeros.
    const AxisSet mixed = set_from("name: mixed\nprovenance: test\n2 0 0\n0 1 -1\n0.2 0.3 0.4\n");
    EXPECT_EQ(frame_float_ops(mixed, Mode::clip, Neighborhood::n9, true), 18u + 24 + 3 * 21 + 9 * 1 + 9 * 2);
    // Two scaled components of one magnitude share their sum: YCoCg's Y (0.5, 1, 0.5) and Cg
    // (-0.5, 1, -0.5) cost one multiply-add per projection and one add per color for x + z.
    const AxisSet ycocg = set_from("name: y\nprovenance: test\n0.25 0.5 0.25\n0.5 0 -0.5\n-0.25 0.5 -0.25\n");
    EXPECT_EQ(frame_float_ops(ycocg, Mode::clip, Neighborhood::n9, false), 18u + 3 * 23 + 10 * (1 + 1 + 1) + 10);
}

TEST(AnalyticCost, EmittedDefaultsSpendTheirFramesCountPlusTheirConstantStarts) {
    auto specs = select_variants({}, {}, {});
    ASSERT_TRUE(specs);
    auto built = build_variants(*specs);
    ASSERT_TRUE(built) << built.error().message;
    for (const BuiltVariant& v : *built) {
        SCOPED_TRACE(v.name);
        const VariantSpec& s = v.spec;
        const bool relative = hardened_frame(s.set, s.mode, s.neighborhood) == Frame::relative;
        const std::size_t constant_starts = relative ? 0 : 2 * s.set.axes.size();
        const std::size_t own = frame_float_ops(s.set, s.mode, s.neighborhood, relative);
        const std::size_t emitted = count_float_ops(v.spirv).total();
        EXPECT_LE(analytic_min_float_ops(s.set, s.mode, s.neighborhood), own);
        if (s.mode == Mode::clip) {
            EXPECT_EQ(emitted, own + constant_starts);
        } else { // see analytic_cost.h: the margin's negation may cost a multiply per slab
            EXPECT_GE(emitted, own);
            EXPECT_LE(emitted, own + s.set.axes.size() + 1);
        }
    }
}

} // namespace
} // namespace kdop
