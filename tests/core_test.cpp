// The core: variant keys and names, the built-in set list read from the embedded axis files, and
// output files written as a set.
#include "core/builtin_sets.h"
#include "core/utf8.h"
#include "core/variant_key.h"
#include "core/write_files.h"
#include "generator/axis_set.h"
#include "generator/variant_spec.h"
#include "tests/test_support.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

namespace kdop {
namespace {
namespace fs = std::filesystem;

TEST(VariantKey, EveryBuiltInNameParsesBackToItsKey) {
    std::size_t paper = 0;
    for (const VariantSpec& spec : all_builtin_variants())
        for (Numerics numerics : {Numerics::hardened, Numerics::paper}) {
            if (!spec.key().is_clip() && numerics == Numerics::paper) continue;
            const VariantKey key = spec.key().with(numerics);
            auto parsed = parse_variant_key(key.name());
            ASSERT_TRUE(parsed) << parsed.error().message;
            EXPECT_EQ(*parsed, key) << key.name();
            paper += key.name().ends_with("-paper");
        }
    EXPECT_EQ(paper, 48u); // 24 clips in two forms
    EXPECT_EQ(parse_variant_key("dop16-grass-varclip-n5-loop-paper")->set, "dop16-grass");
    EXPECT_EQ(parse_variant_key("gather-n5")->mode, Mode::gather);
    EXPECT_EQ(parse_variant_key("copy")->name(), "copy");
    EXPECT_EQ(parse_variant_key("my-set-clip-n9")->set, "my-set");
}

TEST(VariantKey, RefusesWhatIsNotAVariantNameAndSaysWhatWasExpected) {
    for (const char* bad : {"", "dop32", "dop32-clip", "dop32-clamp-n9", "dop32-clip-n4", "Dop32-clip-n9",
                            "dop32-clip-n9-paper-loop", "-clip-n9", "a--b-clip-n9", "gather-n3"}) {
        auto parsed = parse_variant_key(bad, "--variants");
        ASSERT_FALSE(parsed) << bad;
        EXPECT_EQ(parsed.error().message.rfind(fmt::format("--variants: '{}' is not a variant name", bad), 0), 0u)
            << parsed.error().message;
    }
}

TEST(VariantKey, LoopFormAndPaperTwinAreTheSameVariantOtherwise) {
    const VariantKey key = *parse_variant_key("dop22-varclip-n5");
    EXPECT_EQ(key.with(Form::loop).name(), "dop22-varclip-n5-loop");
    EXPECT_EQ(key.with(Numerics::paper).name(), "dop22-varclip-n5-paper");
    EXPECT_EQ(key.with(Form::loop).with(Form::unrolled), key);
    EXPECT_LT(gather_key(Neighborhood::n9), key); // ordered, so keys can index maps
}

// The list of built-in sets is read from the embedded files: each file's stem is its set's name,
// and the order is by axis count, then name.
TEST(BuiltinSets, AreTheEmbeddedAxisFilesNamedByTheirStemAndOrderedByAxisCount) {
    ASSERT_EQ(builtin_set_list(), "aabb, ycocg, dop16-asphalt, dop16-grass, dop22, dop32");
    std::size_t previous_axes = 0;
    for (const std::string& name : builtin_set_names()) {
        auto set = resolve_axis_set(name);
        ASSERT_TRUE(set) << set.error().message;
        EXPECT_EQ(set->name, name) << builtin_set_path(name) << " names another set";
        EXPECT_GE(set->axes.size(), previous_axes) << name;
        previous_axes = set->axes.size();
    }
    EXPECT_FALSE(builtin_set_text("dop16"));
    EXPECT_FALSE(is_builtin_set("shader_templates/axis_sets/dop22.axes"));
}

TEST(WriteFiles, WritesEveryFileOrNone) {
    test::TempDir dir;
    test::write_file(dir / "blocker", "a file where a directory is needed");
    auto failed = write_files_atomically({{dir / "out" / "a.csv", "a"}, {dir / "blocker" / "b.csv", "b"}});
    ASSERT_FALSE(failed);
    EXPECT_NE(failed.error().message.find("blocker"), std::string::npos) << failed.error().message;
    EXPECT_FALSE(fs::exists(dir / "out")) << "the folder made for the set goes with it";
    for (const auto& entry : fs::recursive_directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().string().find("kdop-partial"), std::string::npos) << entry.path();

    ASSERT_TRUE(write_files_atomically({{dir / "out" / "a.csv", "a"}, {dir / "out" / "b.csv", "b"}}));
    EXPECT_EQ(test::read_file(dir / "out" / "b.csv"), "b");
}

TEST(WriteFiles, AnUnchangedFileKeepsItsTimeStamp) {
    test::TempDir dir;
    const fs::path a = dir / "a.h", b = dir / "b.h";
    ASSERT_TRUE(write_files_atomically({{a, "same"}, {b, "old!"}}));
    const auto long_ago = fs::file_time_type::clock::now() - std::chrono::hours(24);
    fs::last_write_time(a, long_ago);
    fs::last_write_time(b, long_ago);

    ASSERT_TRUE(write_files_atomically({{a, "same"}, {b, "new!"}})); // b: same size, other bytes
    EXPECT_EQ(fs::last_write_time(a), long_ago) << "rewriting identical bytes must not touch the file";
    EXPECT_GT(fs::last_write_time(b), long_ago);
    EXPECT_EQ(test::read_file(b), "new!");
    for (const auto& entry : fs::directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().string().find("kdop-partial"), std::string::npos) << entry.path();
}

TEST(WriteFiles, OutputDirectoryIsCheckedBeforeAnyWork) {
    test::TempDir dir;
    EXPECT_TRUE(check_output_directory(dir / "new" / "deeper"));
    EXPECT_FALSE(fs::exists(dir / "new")) << "checking must create nothing";
    auto here = check_output_directory(fs::path("result.png").parent_path());
    EXPECT_TRUE(here) << "the folder of a bare file name is the current directory: " << here.error().message;
    test::write_file(dir / "file", "");
    auto not_dir = check_output_directory(dir / "file" / "out", "--out");
    ASSERT_FALSE(not_dir);
    EXPECT_NE(not_dir.error().message.find("is not a directory"), std::string::npos) << not_dir.error().message;
    auto proc = check_output_directory("/proc/x", "--out");
    ASSERT_FALSE(proc);
    EXPECT_EQ(proc.error().message.rfind("--out: /proc/x: cannot create files in /proc", 0), 0u)
        << proc.error().message;
}

// Exactly what JSON writers accept: table 3-7's sequences, nothing shorter, longer or outside it.
TEST(Utf8, FindsTheFirstByteThatIsNotWellFormed) {
    using namespace std::string_view_literals;
    for (std::string_view good : {""sv, "plain"sv, "caf\xc3\xa9"sv, "\xe0\xa0\x80"sv, "\xed\x9f\xbf"sv,
                                  "\xf0\x90\x80\x80"sv, "\xf4\x8f\xbf\xbf"sv, "nul \0 is a byte"sv})
        EXPECT_EQ(first_non_utf8_byte(good), std::nullopt) << good;
    const std::pair<std::string_view, std::size_t> bad[] = {
        {"caf\xe9"sv, 3},          // Latin-1
        {"\x80"sv, 0},             // a continuation byte alone
        {"\xc0\xaf"sv, 0},         // overlong '/'
        {"\xc1\xbf"sv, 0},         // overlong
        {"\xe0\x9f\xbf"sv, 0},     // overlong three bytes
        {"\xed\xa0\x80"sv, 0},     // a surrogate
        {"\xf0\x8f\xbf\xbf"sv, 0}, // overlong four bytes
        {"\xf4\x90\x80\x80"sv, 0}, // past U+10FFFF
        {"\xf5\x80\x80\x80"sv, 0},
        {"ok\xff"sv, 2},
        {"ab\xe2\x82"sv, 2}, // cut short
        {"\xe2\x82x"sv, 0},
    };
    for (const auto& [text, at] : bad) EXPECT_EQ(first_non_utf8_byte(text), std::optional(at)) << text;
}

} // namespace
} // namespace kdop
