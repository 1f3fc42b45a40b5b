// Axis-set files: the accepted spellings, the built-in sets' numbers, and every refusal with its
// file:line and reason.
#include "core/builtin_sets.h"
#include "fit/fitted_set.h"
#include "generator/axis_set.h"
#include "generator/variant_spec.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kdop {
namespace {

constexpr const char* kHeader = "name: test\nprovenance: unit test\n";

Result<AxisSet> parse(const std::string& axes) { return parse_axis_set(std::string(kHeader) + axes, "t.axes"); }

std::string error_of(const std::string& text) {
    auto set = parse_axis_set(text, "t.axes");
    EXPECT_FALSE(set.has_value()) << "accepted:\n" << text;
    return set ? "" : set.error().message;
}

TEST(AxisSet, AcceptsSpacesCommasVec3WrappersCommentsAndTrailingCommas) {
    auto set = parse("# leading comment\n"
                     "1 0 0\n"
                     "0, 1, 0   # comment after an axis\n"
                     "vec3(0.0, 0.0, 1.0),\n"
                     "  vec3( 0.5 ,-0.25,  +1e-1 ) \n"
                     "\n"
                     "0.3,0.4,-0.5,\n");
    ASSERT_TRUE(set) << set.error().message;
    EXPECT_EQ(set->name, "test");
    EXPECT_EQ(set->provenance, "unit test");
    ASSERT_EQ(set->axes.size(), 5u);
    EXPECT_EQ(set->axes[0].direction, glm::dvec3(1, 0, 0));
    EXPECT_EQ(set->axes[3].direction, glm::dvec3(0.5, -0.25, 0.1));
    EXPECT_EQ(set->axes[4].direction, glm::dvec3(0.3, 0.4, -0.5));
    EXPECT_EQ(set->axes[0].line, 4);
    EXPECT_EQ(set->axes[4].line, 9);
}

TEST(AxisSet, BuiltInSetsHoldThePublishedNumbers) {
    // Spot checks against the supplement's listings (first and last axis of each k-DOP listing)
    // and the YCoCg transform rows; axis counts give k.
    struct Expect {
        const char* name;
        size_t axes;
        glm::dvec3 first, last;
    };
    const Expect expected[] = {
        {"aabb", 3, {1, 0, 0}, {0, 0, 1}},
        {"ycocg", 3, {0.25, 0.5, 0.25}, {-0.25, 0.5, -0.25}},
        {"dop16-grass", 8, {-0.663315, 0.729578, -0.166518}, {0.488190, -0.812612, 0.318327}},
        {"dop16-asphalt", 8, {0.997167, -0.054820, 0.051500}, {0.898010, -0.436338, -0.056459}},
        {"dop22", 11, {1, 0, 0}, {0.656800, -0.655635, 0.372501}},
        {"dop32", 16, {1, 0, 0}, {-0.554854, -0.041550, -0.830910}},
    };
    ASSERT_EQ(builtin_set_names().size(), std::size(expected));
    for (const Expect& e : expected) {
        auto set = resolve_axis_set(e.name);
        ASSERT_TRUE(set) << set.error().message;
        EXPECT_EQ(set->name, e.name);
        EXPECT_FALSE(set->provenance.empty());
        ASSERT_EQ(set->axes.size(), e.axes) << e.name;
        EXPECT_EQ(set->axes.front().direction, e.first) << e.name;
        EXPECT_EQ(set->axes.back().direction, e.last) << e.name;
    }
}

TEST(AxisSet, RefusesUnparseableNumbers) {
    EXPECT_EQ(error_of(std::string(kHeader) + "1 0 0\n0 1 zero\n"), "t.axes:4: 'zero' is not a number");
    EXPECT_EQ(error_of(std::string(kHeader) + "1 0 0\n0 1 0x1\n"), "t.axes:4: '0x1' is not a number");
    EXPECT_EQ(error_of(std::string(kHeader) + "1,,0 0\n"), "t.axes:3: empty number between commas");
    EXPECT_EQ(error_of(std::string(kHeader) + "vec3(1, 0, 0\n"), "t.axes:3: expected vec3(x, y, z)");
}

TEST(AxisSet, RefusesLinesWithOtherThanThreeNumbers) {
    EXPECT_EQ(error_of(std::string(kHeader) + "1 0\n"), "t.axes:3: expected 3 numbers (x y z), found 2");
    EXPECT_EQ(error_of(std::string(kHeader) + "1 0 0 0\n"), "t.axes:3: expected 3 numbers (x y z), found 4");
    EXPECT_EQ(error_of(std::string(kHeader) + "vec3(1, 0)\n"), "t.axes:3: expected 3 numbers (x y z), found 2");
}

TEST(AxisSet, RefusesZeroNanAndInfiniteAxes) {
    EXPECT_EQ(error_of(std::string(kHeader) + "0 0 0\n"), "t.axes:3: axis has zero length");
    EXPECT_EQ(error_of(std::string(kHeader) + "1 nan 0\n"), "t.axes:3: axis component is NaN");
    EXPECT_EQ(error_of(std::string(kHeader) + "inf 0 0\n"), "t.axes:3: axis component is infinite");
    EXPECT_EQ(error_of(std::string(kHeader) + "1e400 0 0\n"), "t.axes:3: '1e400' is out of range for a double");
}

TEST(AxisSet, RefusesDuplicateAndAntiparallelAxes) {
    EXPECT_EQ(error_of(std::string(kHeader) + "1 0 0\n0 1 0\n2 0 0\n"), "t.axes:5: axis duplicates the axis on line 3");
    EXPECT_EQ(error_of(std::string(kHeader) + "1 1 0\n0 0 1\n-0.5 -0.5 0\n"),
              "t.axes:5: axis is antiparallel to the axis on line 3 (both bound the same slab)");
    // Equal up to the 6-decimal rounding of published listings counts as a duplicate...
    EXPECT_EQ(error_of(std::string(kHeader) + "0.577350 0.577350 0.577350\n0.577351 0.577350 0.577350\n"),
              "t.axes:4: axis duplicates the axis on line 3");
    // ...while a real difference in the third decimal does not.
    EXPECT_TRUE(parse("1 0 0\n0 1 0\n0 0 1\n0.577 0.577 0.577\n0.578 0.577 0.577\n"));
}

TEST(AxisSet, RefusesSetsThatDoNotBoundARegion) {
    EXPECT_EQ(error_of(std::string(kHeader) + "1 0 0\n0 1 0\n1 1 0\n1 -2 0\n"),
              "t.axes: the 4 axes do not span 3-D space (fewer than 3, or all in one plane), so the k-DOP "
              "would not bound a region");
    EXPECT_EQ(error_of(std::string(kHeader) + "1 0 0\n0 1 0\n"),
              "t.axes: the 2 axes do not span 3-D space (fewer than 3, or all in one plane), so the k-DOP "
              "would not bound a region");
}

TEST(AxisSet, RefusesMissingOrBadHeaderLines) {
    EXPECT_EQ(error_of("provenance: x\n1 0 0\n0 1 0\n0 0 1\n"), "t.axes: missing 'name:' line");
    EXPECT_EQ(error_of("name: a\n1 0 0\n0 1 0\n0 0 1\n"),
              "t.axes: missing 'provenance:' line (say where the numbers come from)");
    EXPECT_EQ(error_of("name: a\nname: b\n"), "t.axes:2: second 'name:' line (the first is on line 1)");
    EXPECT_EQ(error_of("nmae: a\n"), "t.axes:1: unknown key 'nmae' (expected 'name:', 'provenance:' or 'color_map:')");
    EXPECT_EQ(error_of("name:\n"), "t.axes:1: 'name:' has no value");
    EXPECT_NE(error_of("name: My_Set\n").find("t.axes:1: set name 'My_Set' is not valid"), std::string::npos);
}

// `color_map:` records the space a fitted set was fitted in; a set without it says nothing.
TEST(AxisSet, ReadsTheColorMapItWasFittedIn) {
    const std::string axes = "1 0 0\n0 1 0\n0 0 1\n";
    auto plain = parse_axis_set(std::string(kHeader) + axes, "t.axes");
    ASSERT_TRUE(plain) << plain.error().message;
    EXPECT_FALSE(plain->color_map);
    auto log = parse_axis_set(std::string(kHeader) + "color_map: log\n" + axes, "t.axes");
    ASSERT_TRUE(log) << log.error().message;
    EXPECT_EQ(*log->color_map, (ColorMap{ColorMap::Kind::log, 1}));
    auto gamma = parse_axis_set(std::string(kHeader) + "color_map: gamma:0.5\n" + axes, "t.axes");
    ASSERT_TRUE(gamma) << gamma.error().message;
    EXPECT_EQ(*gamma->color_map, (ColorMap{ColorMap::Kind::power, 0.5f}));
    EXPECT_EQ(error_of(std::string(kHeader) + "color_map: srgb\n" + axes),
              "t.axes:3: color_map: 'srgb' is not a color map; use linear, gamma:G (G from 0.01 to 100) or log");
    EXPECT_EQ(error_of(std::string(kHeader) + "color_map: log\ncolor_map: log\n" + axes),
              "t.axes:4: second 'color_map:' line (the first is on line 3)");
}

// gamma:G is kept as given, every digit: a file records the value the user wrote (gamma:1.00000001
// was written as gamma:1, the float it computes with) and reads back the same. G is a decimal from
// 0.01 to 100: below, the float round trip c -> c^G -> c loses about 6e-8 / G of each color, and
// gamma:1e-300 was 0 in float (every color mapped to 1, and a file saying gamma:0 that no command
// reads); hex and spaces, which strtod took, are refused.
TEST(AxisSet, AColorMapsGammaIsKeptAsGiven) {
    for (const char* given :
         {"gamma:1.00000001", "gamma:2.2", "gamma:0.45454545454545453", "gamma:0.01", "gamma:100"}) {
        SCOPED_TRACE(given);
        auto map = parse_color_map(given);
        ASSERT_TRUE(map) << map.error().message;
        EXPECT_EQ(to_string(*map), given);
        auto file =
            fitted_set_file({"g", "the test's", {}, *map}, std::vector<glm::dvec3>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
        ASSERT_TRUE(file) << file.error().message;
        EXPECT_NE(file->find(std::string("\ncolor_map: ") + given + "\n"), std::string::npos) << *file;
        auto parsed = parse_axis_set(*file, "g.axes");
        ASSERT_TRUE(parsed) << parsed.error().message;
        EXPECT_EQ(*parsed->color_map, *map);
    }
    // The map computes in float, as the resolve's shader does.
    EXPECT_EQ(map_color(*parse_color_map("gamma:1.00000001"), glm::vec3(0.5f)), glm::vec3(0.5f));
    for (const char* bad :
         {"gamma:1e-300", "gamma:0.001", "gamma:0", "gamma:-2", "gamma:101", "gamma:0x10", "gamma:0x1p1", "gamma: 2",
          "gamma:2 ", "gamma:+2", "gamma:inf", "gamma:nan", "gamma:", "gamma:2e"}) {
        auto map = parse_color_map(bad);
        ASSERT_FALSE(map) << bad << " taken as " << to_string(*map);
        EXPECT_NE(map.error().message.find("must be a number from 0.01 to 100"), std::string::npos)
            << map.error().message;
    }
    EXPECT_NE(parse_color_map("gamma:1e-300").error().message.find("1e-300 is 0 in float, mapping every color to 1"),
              std::string::npos);
    EXPECT_NE(parse_color_map("gamma:0.001").error().message.find("--color-map log"), std::string::npos);
}

// What the adversarial run found: each is now accepted as meant or refused with a message that
// says what is wrong, at the right line, without echoing raw bytes.
TEST(AxisSet, ByteOrderMarksLineEndsSignsAndControlCharacters) {
    auto bom = parse_axis_set("\xEF\xBB\xBFname: a\r\nprovenance: x\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\n", "t.axes");
    ASSERT_TRUE(bom) << bom.error().message; // a byte-order mark and CRLF line ends are a plain file
    EXPECT_EQ(bom->name, "a");
    EXPECT_EQ(bom->provenance, "x");
    EXPECT_EQ(error_of("name: a\nprovenance: x\rlayout(binding = 9) buffer B { float b; };\n"),
              "t.axes:2: control character 0x0d; axis files are plain text");
    EXPECT_EQ(error_of(std::string(kHeader) + "1 0 0\n0 1 \x1b[31m0\n"),
              "t.axes:4: control character 0x1b; axis files are plain text");
    EXPECT_EQ(error_of(std::string(kHeader) + "+-1 0 0\n"), "t.axes:3: '+-1' is not a number");
    EXPECT_EQ(error_of(std::string(kHeader) + "++1 0 0\n"), "t.axes:3: '++1' is not a number");
    const std::string long_token(100000, '7');
    const std::string message = error_of(std::string(kHeader) + "1 0 x" + long_token + "\n");
    EXPECT_EQ(message, "t.axes:3: 'x777777777777777777777777777777777777777'… is not a number");
    EXPECT_EQ(error_of(std::string(kHeader) + "1 0 \xff\n"), "t.axes:3: byte 0xff (column 5) is not UTF-8; axis "
                                                             "files are UTF-8 text");
}

// Text that is not UTF-8 is refused where the file is read, naming its line: a Latin-1 provenance
// was accepted, then `kdop gen` and `kdop-gen --json` failed at the end with nlohmann's "invalid
// UTF-8 byte", naming neither the file nor the line (issue 58, finding 7).
TEST(AxisSet, RefusesTextThatIsNotUtf8NamingTheLine) {
    const std::string axes = "1 0 0\n0 1 0\n0 0 1\n";
    EXPECT_EQ(error_of("name: a\nprovenance: caf\xe9\n" + axes),
              "t.axes:2: byte 0xe9 (column 16) is not UTF-8; axis files are UTF-8 text");
    EXPECT_EQ(error_of("name: a\nprovenance: x\n# r\xe9sum\xe9\n" + axes),
              "t.axes:3: byte 0xe9 (column 4) is not UTF-8; axis files are UTF-8 text");
    EXPECT_NE(error_of("name: a\nprovenance: \xc0\xaf overlong\n" + axes).find("t.axes:2: byte 0xc0"),
              std::string::npos);
    EXPECT_NE(error_of("name: a\nprovenance: \xed\xa0\x80 surrogate\n" + axes).find("t.axes:2: byte 0xed"),
              std::string::npos);
    auto utf8 = parse_axis_set("name: a\nprovenance: caf\xc3\xa9 \xf0\x9f\x8c\xb2\n" + axes, "t.axes");
    ASSERT_TRUE(utf8) << utf8.error().message;
    EXPECT_EQ(utf8->provenance, "caf\xc3\xa9 \xf0\x9f\x8c\xb2");
}

// Components far from 1 are directions like any other: compared and spanned after scaling, so
// 1e200 neither overflows into "antiparallel" nor 1e-200 underflows into "zero length".
TEST(AxisSet, HugeAndTinyComponentsAreDirectionsLikeAnyOther) {
    auto huge = parse(std::string("1e200 0 0\n0 2e300 0\n0 0 1e-300\n1e200 1e200 0\n"));
    ASSERT_TRUE(huge) << huge.error().message;
    EXPECT_EQ(huge->axes.size(), 4u);
    EXPECT_EQ(unit_direction({0, 0, 1e-300}), glm::dvec3(0, 0, 1));
    EXPECT_EQ(error_of(std::string(kHeader) + "1e200 0 0\n-2e300 0 0\n"),
              "t.axes:4: axis is antiparallel to the axis on line 3 (both bound the same slab)");
    EXPECT_EQ(error_of(std::string(kHeader) + "1e-300 1e-300 0\n3 3 0\n"),
              "t.axes:4: axis duplicates the axis on line 3");
}

TEST(AxisSet, SetNamesMapOneToOneOntoIdentifiers) {
    for (const char* good : {"a", "dop16-grass", "x2-y3", "k9"}) EXPECT_TRUE(is_valid_set_name(good)) << good;
    for (const char* bad : {"", "A", "9a", "a_b", "a--b", "a-", "-a", "a b", "a.b"})
        EXPECT_FALSE(is_valid_set_name(bad)) << bad;
}

TEST(VariantSelection, RefusesUnknownNamesRepeatsAndNameClashes) {
    auto error = [](std::vector<std::string> sets, std::vector<std::string> modes, std::vector<std::string> ns) {
        auto specs = select_variants(sets, modes, ns);
        EXPECT_FALSE(specs.has_value());
        return specs ? "" : specs.error().message;
    };
    EXPECT_EQ(error({"nope"}, {}, {}),
              "--sets: 'nope' is not a built-in axis set (aabb, ycocg, dop16-asphalt, dop16-grass, dop22, dop32) "
              "nor a readable file");
    EXPECT_EQ(error({"aabb", "aabb"}, {}, {}), "--sets: 'aabb' is given twice");
    EXPECT_EQ(error({}, {"clamp"}, {}), "--modes: unknown mode 'clamp' (expected clip or varclip)");
    EXPECT_EQ(error({}, {"clip", "clip"}, {}), "--modes: 'clip' is given twice");
    EXPECT_EQ(error({}, {}, {"n4"}), "--neighborhoods: unknown neighborhood 'n4' (expected n9 or n5)");
}

TEST(VariantSelection, DefaultsAreEverySetModeAndNeighborhoodInOrder) {
    auto specs = select_variants({}, {}, {});
    ASSERT_TRUE(specs);
    ASSERT_EQ(specs->size(), 24u);
    EXPECT_EQ(variant_name((*specs)[0]), "aabb-clip-n9");
    EXPECT_EQ(variant_name((*specs)[3]), "aabb-varclip-n5");
    EXPECT_EQ(variant_name((*specs)[23]), "dop32-varclip-n5");
}

} // namespace
} // namespace kdop
