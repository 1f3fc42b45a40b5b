// Reliability, round 3 (issue 41), the findings of an adversarial user, each as a test that failed
// before its fix: outputs that are special files, hostile names in every language kdop writes,
// colors a map takes beyond float, a frame swapped for a link mid-run, odd EXR channels, depth that
// is not finite, the command-line contract (one table over every numeric option), no Vulkan driver.
// The HDR-FLIP of huge values is in hdr_flip_test.cpp and device_flip_test.cpp, the Vulkan 1.3
// workgroup size in target_env_test.cpp, the crash of a run in trust_test.cpp.
#include "color_map.h"
#include "escaped_text.h"
#include "image_io.h"
#include "output_set.h"
#include "registry_writer.h"
#include "run_metadata.h"
#include "sequence.h"
#include "shown_text.h"
#include "table.h"
#include "test_support.h"
#include "write_files.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <new>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>

namespace kdop {
namespace {
namespace fs = std::filesystem;

std::string kdop(const std::string& args) { return test::kdop_binary() + " " + args; }

// A FIFO and, where this process may make one (root), a character device like /dev/null, in `dir`.
std::vector<fs::path> special_files(const fs::path& dir) {
    std::vector<fs::path> out{dir / "fifo.exr"};
    EXPECT_EQ(mkfifo(out[0].c_str(), 0644), 0) << std::strerror(errno);
    if (mknod((dir / "null.exr").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) out.push_back(dir / "null.exr");
    return out;
}

bool still_special(const fs::path& p) {
    const fs::file_type type = fs::symlink_status(p).type();
    return type == fs::file_type::fifo || type == fs::file_type::character;
}

// ---------------------------------------------------------------------------------------------
// Outputs

TEST(SpecialFiles, AnOutputSetNeverReplacesADeviceOrAFifo) {
    test::TempDir dir;
    for (const fs::path& special : special_files(dir.path())) {
        auto r = write_files_atomically({{dir / "a.csv", "a"}, {special, "b"}});
        ASSERT_FALSE(r) << special;
        EXPECT_NE(r.error().message.find(special.string() + ": is a"), std::string::npos) << r.error().message;
        EXPECT_TRUE(still_special(special)) << special;
        EXPECT_FALSE(fs::exists(dir / "a.csv")) << "nothing of the set is written";
        // A link to one is refused as what it leads to.
        fs::create_symlink(special, dir / "link");
        EXPECT_FALSE(check_output_file(dir / "link", "--out"));
        fs::remove(dir / "link");
    }
}

TEST(SpecialFiles, EveryCommandRefusesThemUpFrontWithExit2) {
    test::TempDir dir;
    const std::string image = (dir / "image.exr").string();
    ASSERT_TRUE(write_image(image, Image(8, 8, {0.5f, 0.25f, 0.125f, 1})));
    for (const fs::path& special : special_files(dir.path())) {
        const std::string s = special.string();
        const std::string commands[] = {
            kdop("optimize --sphere --axes 3 --out " + s),
            kdop("run --variant aabb-clip-n9 --current " + image + " --history " + image + " --out " + s),
            kdop("flip --reference " + image + " --test " + image + " --out " + s + " --cpu"),
            test::kdop_gen_binary() + " registry --sets aabb --modes clip --neighborhoods n9 --namespace a --header " +
                s + " --source " + (dir / "a.cpp").string(),
            test::kdop_gen_binary() + " registry --sets aabb --modes clip --neighborhoods n9 --namespace a --header " +
                (dir / "a.h").string() + " --source " + s,
        };
        for (const std::string& command : commands) {
            auto r = test::run("timeout 60 " + command);
            EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
            EXPECT_NE(r.err.find(s + ": is a"), std::string::npos) << r.err;
            EXPECT_TRUE(still_special(special)) << command;
        }
    }
    EXPECT_FALSE(fs::exists(dir / "a.cpp"));
    EXPECT_FALSE(fs::exists(dir / "a.h"));
}

// A writer that throws (an image library out of memory) leaves neither a temporary nor a changed set.
TEST(SpecialFiles, AWriterThatThrowsLeavesNoTemporary) {
    test::TempDir dir;
    ASSERT_TRUE(write_files_atomically({{dir / "out" / "kept.csv", "before"}}));
    const OutputFile first{dir / "out" / "kept.csv", "after"};
    OutputWriter throwing{dir / "out" / "run.exr", [](const fs::path& temporary) -> Result<void> {
                              std::ofstream(temporary) << "half an image";
                              throw std::bad_alloc();
                          }};
    EXPECT_THROW(write_atomically({content_writer(first), throwing}), std::bad_alloc);
    std::vector<std::string> left;
    for (const auto& entry : fs::directory_iterator(dir / "out")) left.push_back(entry.path().filename().string());
    EXPECT_EQ(left, std::vector<std::string>{"kept.csv"});
    EXPECT_EQ(test::read_file(dir / "out" / "kept.csv"), "before");
}

// ---------------------------------------------------------------------------------------------
// Names from outside in the languages kdop writes

// Quotes, backslashes, a line break, $, #, ;, a '?' pair (a trigraph before C++17), non-ASCII.
const std::string kHostile[] = {"x\" ? (__builtin_puts(\"INJECTED\"), \"y\") : \"",
                                "back\\slash\\",
                                "two\nlines",
                                "$dollar#hash;semi",
                                "??=trigraph",
                                "caf\xc3\xa9",
                                "tab\there"};

TEST(HostileNames, EscapedTextHoldsEveryByteAndNoMarkup) {
    EXPECT_EQ(cpp_string_literal("a\"b\\c\n?\x01\xc3\xa9"), "\"a\\\"b\\\\c\\n\\?\\001\\303\\251\"");
    EXPECT_EQ(line_comment_text("ends with \\"), "ends with \\x5c");
    EXPECT_EQ(line_comment_text("a\nb\x1b"), "a\\x0ab\\x1b");
    EXPECT_EQ(markdown_text("a|b <script> *c* [d](e) `f`"), "a\\|b \\<script\\> \\*c\\* \\[d\\](e) \\`f\\`");
    EXPECT_EQ(markdown_text("one\ntwo"), "one\\x0atwo");
    EXPECT_EQ(markdown_code("kdop `rm` x"), "``kdop `rm` x``");
    EXPECT_EQ(markdown_code("`a"), "`` `a ``");
    using namespace std::string_view_literals;
    EXPECT_EQ(terminal_text("\x1b[31mRED\x1b[0m\0x\n\t\xc3\xa9"sv), "\\x1b[31mRED\\x1b[0m\\x00x\n\t\xc3\xa9");
}

// Each hostile name as a project shader's file name: the registry compiles, and the program built
// from it lists every name as it is, running nothing else (before: the first name printed INJECTED).
TEST(HostileNames, TheRegistryHoldsShaderNamesAsTheyAre) {
    test::TempDir dir;
    std::string shaders;
    for (const std::string& name : kHostile) {
        const fs::path file = dir / (name + ".comp");
        test::write_file(file, "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
        shaders += " '" + std::regex_replace(file.string(), std::regex("'"), "'\\''") + "'";
    }
    auto gen = test::run(test::kdop_gen_binary() +
                         " registry --sets aabb --modes clip --neighborhoods n9 --namespace "
                         "app --header " +
                         (dir / "registry.h").string() + " --source " + (dir / "registry.cpp").string() + " --shaders" +
                         shaders);
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
    test::write_file(dir / "main.cpp", "#include \"registry.h\"\n#include <cstdio>\n"
                                       "int main() { for (const kdop::Variant& v : app::variants()) "
                                       "std::printf(\"%s|\", v.name); }\n");
    const std::string program = (dir / "program").string();
    auto built =
        test::run("g++ -std=c++17 -I" + std::string(KDOP_VARIANT_HEADERS_DIR) + " -I" + dir.path().string() + " " +
                  (dir / "main.cpp").string() + " " + (dir / "registry.cpp").string() + " -o " + program);
    ASSERT_EQ(built.exit_code, 0) << built.err;
    auto ran = test::run(program);
    ASSERT_EQ(ran.exit_code, 0) << ran.err;
    std::string expected = "aabb-clip-n9|";
    for (const std::string& name : kHostile) expected += name + "|";
    EXPECT_EQ(ran.out, expected);
    // The comment that lists them stays one line.
    const std::string header = test::read_file(dir / "registry.h");
    for (const std::string& line : std::vector<std::string>{"// 1 k-DOP", "#pragma once"})
        EXPECT_NE(header.find("\n" + line), std::string::npos) << header;
}

TEST(HostileNames, MarkdownTablesAndJsonHoldThemAsTheyAre) {
    Table table({Column("sequence", "", Shown::text), Column("ghosting")});
    for (const std::string& name : kHostile) table.add({name, 0.5});
    table.add({std::string("a|b\n| c | d |"), 0.25});
    table.add({std::string("<img src=x onerror=alert(1)>"), 0.25});
    const std::string markdown = table.markdown();
    std::istringstream lines(markdown);
    std::size_t rows = 0;
    for (std::string line; std::getline(lines, line); ++rows) {
        // Three unescaped '|' a row: the row's cells stay two.
        const std::string unescaped = std::regex_replace(line, std::regex(R"(\\.)"), "");
        EXPECT_EQ(std::count(unescaped.begin(), unescaped.end(), '|'), 3) << line;
        EXPECT_EQ(unescaped.find('<'), std::string::npos) << line;
    }
    EXPECT_EQ(rows, std::size(kHostile) + 4);
    // Bytes that are not UTF-8 are replaced in JSON, not a crash of the whole write.
    Table invalid({Column("name", "", Shown::text)});
    invalid.add({std::string("caf\xe9")});
    test::TempDir dir;
    auto outputs = OutputSet::prepare(dir / "out");
    ASSERT_TRUE(outputs);
    outputs->add_table("t", invalid, describe_run());
    ASSERT_TRUE(outputs->write());
    const auto json = nlohmann::json::parse(test::read_file(dir / "out" / "t.json"));
    EXPECT_EQ(json["rows"][0]["name"], "caf\xef\xbf\xbd");
    // The command line in a report cannot close its code span.
    EXPECT_EQ(markdown_code("kdop taa --out '``x'"), "```kdop taa --out '``x'```");
}

TEST(HostileNames, ANamespaceMustBeOneAndAHeaderNotItsSource) {
    EXPECT_FALSE(cpp_namespace_problem("app::taa"));
    for (const char* bad : {"int", "app::class", "a-b", "__x", "_X", "x::"})
        EXPECT_TRUE(cpp_namespace_problem(bad)) << bad;
    test::TempDir dir;
    EXPECT_TRUE(registry_files_problem(dir / "a.cpp", dir / "a.cpp", {}));
    EXPECT_TRUE(registry_files_problem(dir / "a.h", dir / "sub" / ".." / "a.h", {}));
    EXPECT_TRUE(registry_files_problem(dir / "a\"b.h", dir / "a.cpp", {}));
    EXPECT_FALSE(registry_files_problem(dir / "a.h", dir / "a.cpp", dir / "a.d"));
    auto r = test::run(test::kdop_gen_binary() + " registry --sets aabb --namespace int --header " +
                       (dir / "a.h").string() + " --source " + (dir / "a.cpp").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--namespace: 'int' holds the C++ keyword 'int'"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "a.h"));
}

// cmake/KdopVariants.cmake refuses, at configure time, the keywords kdop-gen refuses.
TEST(HostileNames, CmakeRefusesTheKeywordsKdopGenRefuses) {
    const std::string cmake = test::read_file(fs::path(KDOP_SOURCE_DIR) / "cmake" / "KdopVariants.cmake");
    const std::smatch found = [&] {
        std::smatch m;
        std::regex_search(cmake, m, std::regex(R"(set\(cpp_keywords([^)]*)\))"));
        return m;
    }();
    ASSERT_FALSE(found.empty());
    std::set<std::string> listed;
    std::istringstream words(found[1].str());
    for (std::string word; words >> word;) listed.insert(word);
    EXPECT_EQ(listed, std::set<std::string>(cpp_keywords().begin(), cpp_keywords().end()));
}

// ---------------------------------------------------------------------------------------------
// Sequences

// A sequence of `frames` frames of w x h in `dir`: color(n) each frame's color, still motion, depth
// where `depth` gives it (NaN allowed), `declared` overriding the size sequence.json states.
struct TestSequence {
    fs::path dir;
    std::uint32_t w = 16, h = 8;
    bool hdr = false;
    std::function<Image(int)> color = [this](int) { return Image(w, h, {0.5f, 0.25f, 0.125f, 1}); };
    std::function<std::optional<Image>(int)> depth = [](int) { return std::nullopt; };
    std::optional<std::pair<int, int>> declared;

    void write(int frames) const {
        fs::create_directories(dir / "color");
        fs::create_directories(dir / "motion");
        fs::create_directories(dir / "depth");
        std::string list;
        for (int n = 0; n < frames; ++n) {
            EXPECT_TRUE(write_image((dir / fmt::format("color/{:04}.exr", n)).string(), color(n)));
            EXPECT_TRUE(write_image((dir / fmt::format("motion/{:04}.exr", n)).string(), Image(w, h, {0, 0, 0, 1})));
            std::string extra;
            if (auto d = depth(n)) {
                EXPECT_TRUE(write_image((dir / fmt::format("depth/{:04}.exr", n)).string(), *d));
                extra = fmt::format(R"(, "depth": "depth/{:04}.exr")", n);
            }
            list += fmt::format(R"({}{{"color": "color/{:04}.exr", "motion": "motion/{:04}.exr"{}}})", n ? ",\n  " : "",
                                n, n, extra);
        }
        test::write_file(dir / "sequence.json",
                         fmt::format("{{\"kdop_sequence\": 1, \"width\": {}, \"height\": {}, \"color\": {{\"range\": "
                                     "\"{}\"}},\n \"frames\": [\n  {}]}}\n",
                                     declared ? declared->first : int(w), declared ? declared->second : int(h),
                                     hdr ? "hdr" : "ldr", list));
    }
};

TEST(SequenceChecks, TheDeclaredSizeIsTheFirstFramesAndDepthIsFinite) {
    test::TempDir dir;
    TestSequence s{dir / "s"};
    s.declared = std::pair{8192, 8192};
    s.write(3);
    auto wrong = read_sequence(s.dir);
    ASSERT_FALSE(wrong);
    EXPECT_NE(wrong.error().message.find("color/0000.exr: 16x8, but " + (s.dir / "sequence.json").string() +
                                         " says 8192x8192"),
              std::string::npos)
        << wrong.error().message;
    s.declared.reset();
    s.depth = [&](int n) { return std::optional(Image(s.w, s.h, {n == 1 ? NAN : 0.5f, 0, 0, 1})); };
    s.write(3);
    auto read = read_sequence(s.dir);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_TRUE(load_frame(*read, 0));
    auto nan = load_frame(*read, 1);
    ASSERT_FALSE(nan);
    EXPECT_NE(nan.error().message.find("depth/0001.exr: pixel (0, 0) holds nan in channel 0; depth must be finite"),
              std::string::npos)
        << nan.error().message;
}

// read_sequence checks that every file lies inside the folder; a frame replaced by a link to a file
// outside it after that check is refused when the frame is read, not read.
TEST(SequenceChecks, AFrameSwappedForALinkOutsideIsRefused) {
    test::TempDir dir;
    TestSequence s{dir / "s"};
    s.write(2);
    ASSERT_TRUE(write_image((dir / "secret.exr").string(), Image(16, 8, {1, 0, 0, 1})));
    auto sequence = read_sequence(s.dir);
    ASSERT_TRUE(sequence) << sequence.error().message;
    fs::remove(s.dir / "color" / "0001.exr");
    fs::create_symlink("../../secret.exr", s.dir / "color" / "0001.exr");
    auto swapped = load_frame(*sequence, 1);
    ASSERT_FALSE(swapped) << "read " << (dir / "secret.exr");
    EXPECT_NE(swapped.error().message.find("now leads outside the sequence's folder"), std::string::npos)
        << swapped.error().message;
    // A link that stays inside is followed, as read_sequence follows it.
    fs::remove(s.dir / "color" / "0001.exr");
    fs::create_symlink("0000.exr", s.dir / "color" / "0001.exr");
    EXPECT_TRUE(load_frame(*sequence, 1));
    // A FIFO swapped in is refused without waiting for a writer.
    fs::remove(s.dir / "color" / "0001.exr");
    ASSERT_EQ(mkfifo((s.dir / "color" / "0001.exr").c_str(), 0644), 0);
    auto fifo = load_frame(*sequence, 1);
    ASSERT_FALSE(fifo);
    EXPECT_NE(fifo.error().message.find("is no longer a regular file"), std::string::npos) << fifo.error().message;
}

// Y, RY, BY (luminance and chroma) is not RGB, and is refused naming its channels.
TEST(SequenceChecks, ColorComesOnlyFromChannelsNamedRgb) {
    test::TempDir dir;
    auto write = [&](const std::string& name, std::vector<std::string> channels) {
        const std::string path = (dir / name).string();
        auto out = OIIO::ImageOutput::create(path);
        OIIO::ImageSpec spec(4, 2, int(channels.size()), OIIO::TypeDesc::FLOAT);
        spec.channelnames = channels;
        EXPECT_TRUE(out->open(path, spec));
        std::vector<float> pixels(4 * 2 * channels.size(), 0.5f);
        EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        out->close();
        return path;
    };
    auto chroma = read_image(write("chroma.exr", {"Y", "RY", "BY"}));
    ASSERT_FALSE(chroma);
    EXPECT_NE(
        chroma.error().message.find("its channels are Y, BY, RY; kdop reads color from channels named R, G and B"),
        std::string::npos)
        << chroma.error().message;
    EXPECT_TRUE(read_image(write("rgba.exr", {"R", "G", "B", "A"})));
    EXPECT_TRUE(read_image(write("layer.exr", {"diffuse.R", "diffuse.G", "diffuse.B"})));
    EXPECT_FALSE(read_image(write("mixed.exr", {"a.R", "b.G", "c.B"})));
    EXPECT_TRUE(read_data_image(write("motion.exr", {"X", "Y"}), 2)) << "data is not color";
}

} // namespace
} // namespace kdop
