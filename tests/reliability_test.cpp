// Reliability, round 3 (issue 41), the findings of an adversarial user, each as a test that failed
// before its fix: outputs that are special files, hostile names in every language kdop writes,
// colors a map takes beyond float, a frame swapped for a link mid-run, odd EXR channels, depth that
// is not finite, the command-line contract (one table over every numeric option), no Vulkan driver.
// The HDR-FLIP of huge values is in hdr_flip_test.cpp and device_flip_test.cpp, the Vulkan 1.3
// workgroup size in target_env_test.cpp, the crash of a run in trust_test.cpp.
#include "core/color_map.h"
#include "core/escaped_text.h"
#include "core/shown_text.h"
#include "core/write_files.h"
#include "generator/registry_writer.h"
#include "harness/output_set.h"
#include "harness/run_metadata.h"
#include "harness/table.h"
#include "images/image_io.h"
#include "sequence/sequence.h"
#include "tests/test_support.h"

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
#include <thread>

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

// An image written under a set's temporary names its final path in its errors, not the temporary
// (a full disk's error named "0001.kdop-partial-...-5.kdop-partial-...-6.exr").
TEST(SpecialFiles, AWriteErrorNamesTheOutputNotItsTemporary) {
    test::TempDir dir;
    const fs::path temporary = dir / "missing" / "0001.kdop-partial-1-2.exr";
    auto r = write_image_to(temporary, (dir / "out" / "0001.exr").string(), Image(4, 4));
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find((dir / "out" / "0001.exr").string()), std::string::npos) << r.error().message;
    EXPECT_EQ(r.error().message.find("kdop-partial"), std::string::npos) << r.error().message;
}

// ---------------------------------------------------------------------------------------------
// Names from outside in the languages kdop writes

// Quotes, backslashes, a line break, $, #, ;, a '?' pair (a trigraph before C++17), non-ASCII.
const std::string kHostile[] = {"x\" ? (__builtin_puts(\"INJECTED\"), \"y\") : \"",
                                "back\\slash\\",
                                "two\nlines",
                                "$dollar#hash;semi",
                                "?"
                                "?=trigraph",
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
    EXPECT_EQ(markdown_destination("trade-grass.png"), "trade-grass.png");
    EXPECT_EQ(markdown_destination("trade-my (1)>.png"), "<trade-my (1)\\>.png>");
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

// ---------------------------------------------------------------------------------------------
// Commands

// A color that --color-map gamma:10 takes beyond float (60000^10) is refused naming the frame, the
// pixel and the value, by kdop taa (which turned the block black) and kdop optimize (which aborted
// inside GLPK), and so is 1e20 under gamma:2.
TEST(CliReliability, AColorMappedBeyondFloatIsRefusedNamingIt) {
    test::TempDir dir;
    for (auto [value, map] : {std::pair{60000.0f, "gamma:10"}, std::pair{1e20f, "gamma:2"}}) {
        TestSequence s{dir / fmt::format("hdr-{}", map[6])};
        s.hdr = true;
        s.color = [&, value](int n) {
            Image image(s.w, s.h, {0.5f, 0.25f, 0.125f, 1});
            if (n == 2) image.at(5, 3) = {value, 1, 1, 1};
            return image;
        };
        s.write(4);
        const std::string frame = (s.dir / "color" / "0002.exr").string();
        const std::string expected =
            fmt::format("pixel (5, 3) has R {}, which --color-map {} takes to inf", value, map);
        auto taa = test::run(kdop("taa --sequence " + s.dir.string() +
                                  " --warmup 1 --sets aabb --modes clip "
                                  "--timing-rounds 1 --no-charts --color-map " +
                                  map + " --out " + (dir / "taa").string()));
        EXPECT_EQ(taa.exit_code, 1) << taa.err;
        EXPECT_NE(taa.err.find(frame), std::string::npos) << taa.err;
        EXPECT_NE(taa.err.find(expected), std::string::npos) << taa.err;
        auto fit = test::run(kdop("optimize --sequence " + s.dir.string() +
                                  " --axes 3 --starts 1 --iterations 1 "
                                  "--accuracy-samples 0 --color-map " +
                                  map + " --out " + (dir / "fit.axes").string()));
        EXPECT_EQ(fit.exit_code, 1) << fit.err;
        EXPECT_NE(fit.err.find(frame + " pixel"), std::string::npos) << fit.err;
        EXPECT_NE(fit.err.find(expected), std::string::npos) << fit.err;
    }
    EXPECT_FALSE(fs::exists(dir / "taa"));
    EXPECT_FALSE(fs::exists(dir / "fit.axes"));
}

// An all-black frame no longer stops an HDR run: its HDR-FLIP range is defined (the test image's,
// or exposure 0 for a black pair) and the user is told once, naming the frame; a frame of 1e-40,
// which no exposure float can make visible, is refused naming the frame.
TEST(CliReliability, HdrFramesWithoutAnExposureRangeAreMeasuredOrNamed) {
    test::TempDir dir;
    TestSequence s{dir / "dark"};
    s.hdr = true;
    s.color = [&](int n) { return Image(s.w, s.h, n == 3 ? glm::vec4(0, 0, 0, 1) : glm::vec4(4, 2, 1, 1)); };
    s.write(5);
    auto run = test::run(kdop("taa --sequence " + s.dir.string() +
                              " --warmup 1 --sets aabb --modes clip "
                              "--timing-rounds 1 --no-charts --out " +
                              (dir / "taa").string()));
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(
        run.err.find("warning: " + (s.dir / "color" / "0003.exr").string() + " (frame 3): the reference is black"),
        std::string::npos)
        << run.err;
    TestSequence faint{dir / "faint"};
    faint.hdr = true;
    faint.color = [&](int n) {
        return Image(s.w, s.h, n == 2 ? glm::vec4(1e-40f, 1e-40f, 1e-40f, 1) : glm::vec4(4, 2, 1, 1));
    };
    faint.write(4);
    auto refused = test::run(kdop("taa --sequence " + faint.dir.string() +
                                  " --warmup 1 --sets aabb --modes clip "
                                  "--timing-rounds 1 --no-charts --out " +
                                  (dir / "faint-taa").string()));
    EXPECT_EQ(refused.exit_code, 1) << refused.err;
    EXPECT_NE(refused.err.find((faint.dir / "color" / "0002.exr").string() + " (frame 2): ghosting"), std::string::npos)
        << refused.err;
    EXPECT_NE(refused.err.find("beyond the 126 that float can scale by"), std::string::npos) << refused.err;
}

// What a run needs is checked before any frame is made or read: the size a sequence declares, the
// device's limits, depth under --dilate-motion.
TEST(CliReliability, LimitsAreCheckedBeforeTheWork) {
    test::TempDir dir;
    TestSequence s{dir / "big"};
    s.declared = std::pair{8192, 8192};
    s.write(3);
    const std::string taa =
        " --warmup 1 --sets aabb --modes clip --timing-rounds 1 --no-charts --out " + (dir / "taa").string();
    auto declared = test::run(kdop("taa --sequence " + s.dir.string() + taa));
    EXPECT_EQ(declared.exit_code, 1);
    EXPECT_NE(declared.err.find("16x8, but " + (s.dir / "sequence.json").string() + " says 8192x8192"),
              std::string::npos)
        << declared.err;
    // FLIP's maps at 8192x8192 exceed lavapipe's storage buffers (128 MiB); the CPU's FLIP is named.
    auto size = test::run(kdop("taa --scenes grass --size 8192x8192" + taa));
    EXPECT_EQ(size.exit_code, 2);
    EXPECT_NE(size.err.find("--size 8192x8192: "), std::string::npos) << size.err;
    EXPECT_NE(size.err.find("--cpu-flip"), std::string::npos) << size.err;
    s.declared.reset();
    s.write(3);
    auto depth = test::run(kdop("taa --sequence " + s.dir.string() + " --dilate-motion" + taa));
    EXPECT_EQ(depth.exit_code, 1);
    EXPECT_NE(depth.err.find("frames[1] of " + (s.dir / "sequence.json").string() + " has no \"depth\" file"),
              std::string::npos)
        << depth.err;
    for (const auto* r : {&declared, &size, &depth})
        EXPECT_EQ(r->err.find("TAA of"), std::string::npos) << "no work began: " << r->err;
    EXPECT_FALSE(fs::exists(dir / "taa"));
}

// A file name with terminal escapes or a NUL-like byte is shown escaped in every message.
TEST(CliReliability, ControlBytesInNamesAreShownEscaped) {
    test::TempDir dir;
    TestSequence s{dir / "s"};
    s.write(2);
    const std::string red = "\x1b[31mRED\x1b[0m.exr";
    fs::rename(s.dir / "color" / "0001.exr", s.dir / "color" / red);
    std::string json = test::read_file(s.dir / "sequence.json");
    json.replace(json.find("color/0001.exr"), 14, "color/\\u001b[31mRED\\u001b[0m.exr");
    test::write_file(s.dir / "sequence.json", json);
    fs::remove(s.dir / "color" / red);
    fs::create_directory(s.dir / "color" / red); // a folder where the frame should be
    auto r =
        test::run(kdop("taa --sequence " + s.dir.string() + " --warmup 1 --sets aabb --out " + (dir / "taa").string()));
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << "raw escape in: " << shown_text(r.err, 400);
    EXPECT_NE(r.err.find("\\x1b[31mRED"), std::string::npos) << shown_text(r.err, 400);
}

// What README and the reports said that was not so: the accuracy report on one scene-optimized
// 16-DOP; kdop scene's progress, a line per file rather than silence until the end.
TEST(CliReliability, ReportsAndProgressSayWhatHappened) {
    test::TempDir dir;
    auto accuracy = test::run(kdop("accuracy --sets dop16-grass --modes clip --neighborhoods n5 --size 16 "
                                   "--volume-samples 0 --no-charts --out " +
                                   (dir / "a").string()));
    ASSERT_EQ(accuracy.exit_code, 0) << accuracy.err;
    const std::string report = test::read_file(dir / "a" / "report.md");
    EXPECT_NE(report.find("Only dop16-grass was measured"), std::string::npos) << report;
    EXPECT_EQ(report.find("were not measured"), std::string::npos) << report;
    auto scene = test::run(kdop("scene --scenes grass --frames 3 --size 32x32 --out " + (dir / "s").string()));
    ASSERT_EQ(scene.exit_code, 0) << scene.err;
    EXPECT_NE(scene.err.find("grass-ghosting/color/0002.exr"), std::string::npos) << scene.err;
    EXPECT_GE(std::count(scene.err.begin(), scene.err.end(), '\n'), 10) << scene.err;
}

// Every numeric option of every command refuses NaN, the infinities, text and values out of its
// range with exit 2, in one wording, before any work. Each option is tried with a value out of its
// range; every kind of bad value is tried on one real-valued and one whole-numbered option, since
// all of them share those two checks (cli/number_option.h). A kdop process takes about 0.4 s to
// start (its 273 shared libraries), so the cases run two at a time.
TEST(CliCommandLine, EveryBadNumericValueIsExit2) {
    test::TempDir dir;
    const std::string out = " --out " + (dir / "out").string();
    const std::string image = (dir / "i.exr").string();
    ASSERT_TRUE(write_image(image, Image(8, 8, {0.5f, 0.5f, 0.5f, 1})));
    const std::string run = "run --variant aabb-varclip-n9 --current " + image + " --history " + image + out;
    const std::string flip = "flip --reference " + image + " --test " + image;
    const std::string fit = "optimize --images " + image + " --axes 4" + out;
    const std::string sphere = "optimize --sphere --axes 4" + out;
    std::vector<std::string> cases = {run + " --gamma 0",
                                      run + " --repeat 0",
                                      "accuracy" + out + " --gamma -1",
                                      "accuracy" + out + " --size 4097",
                                      "accuracy" + out + " --seed -1",
                                      "accuracy" + out + " --volume-samples 2000000",
                                      "stress" + out + " --gamma -1",
                                      "stress" + out + " --seed 1.5",
                                      "bench" + out + " --repeat 0",
                                      "bench" + out + " --sweep-repeat 0",
                                      "bench" + out + " --callgrind-size 7",
                                      "bench" + out + " --jobs 257",
                                      "bench" + out + " --size 100000x100000",
                                      "gen" + out + " --threads 0",
                                      sphere + " --threads 4294967295",
                                      sphere + " --seed -1",
                                      sphere + " --starts 0",
                                      sphere + " --iterations 0",
                                      sphere + " --time-limit 0",
                                      sphere + " --target 0",
                                      sphere + " --max-nonzero 97",
                                      "optimize --sphere" + out + " --axes 33",
                                      fit + " --memory 0",
                                      fit + " --sample 0",
                                      fit + " --accuracy-samples -1",
                                      flip + " --ppd 1001",
                                      flip + " --distance 0",
                                      flip + " --display-width -1",
                                      flip + " --display-pixels 0",
                                      flip + " --timing 0",
                                      flip + " --hdr --start-exposure 1001",
                                      flip + " --hdr --exposures 0",
                                      "taa" + out + " --warmup 0",
                                      "taa" + out + " --frames 0",
                                      "taa" + out + " --timing-rounds 0",
                                      "taa" + out + " --seed -1",
                                      "taa" + out + " --gamma 0",
                                      "taa" + out + " --current-weight 0",
                                      "taa" + out + " --ppd x",
                                      "taa" + out + " --size 1x1",
                                      "taa" + out + " --reference-samples 1025",
                                      "scene" + out + " --frames 0",
                                      "scene" + out + " --seed -1",
                                      "scene" + out + " --size 1x1",
                                      "textures" + out + " --width 7",
                                      "textures" + out + " --height 16385",
                                      "textures" + out + " --seed -1",
                                      "choose --fit " + dir.path().string() + " --holdout 1" + out +
                                          " --budget-ms 0x10"};
    // strtod's forms beyond decimals: hex (0x10 was taken as 16), hex floats, spaces, "infinity".
    for (const char* value :
         {"nan", "inf", "-inf", "x", "1e999", "-1", "101", "", "0x10", "0x1p4", " 5", "5 ", "1e", "+5", "infinity"})
        cases.push_back(run + " --gamma '" + value + "'");
    for (const char* value : {"nan", "inf", "x", "1e3", "-1", "1025", "", "0x10", "1.5", " 5", "5 ", "+5"})
        cases.push_back("gen" + out + " --threads '" + value + "'");
    std::vector<test::CommandResult> results(cases.size());
    auto worker = [&](std::size_t first) {
        for (std::size_t i = first; i < cases.size(); i += 2) results[i] = test::run("timeout 60 " + kdop(cases[i]));
    };
    std::thread other(worker, 1);
    worker(0);
    other.join();
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const test::CommandResult& r = results[i];
        // The option is the last but one word of the case (the last may be quoted, with spaces).
        const std::string option =
            std::regex_replace(cases[i], std::regex(R"(^.* (--[a-z-]+) ('[^']*'|[^ ]*)$)"), "$1");
        EXPECT_EQ(r.exit_code, 2) << cases[i] << "\n" << r.err;
        EXPECT_TRUE(r.err.starts_with("kdop: " + option + ":")) << cases[i] << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "out"));
    auto list = test::run(kdop("list --sets nosuch"));
    EXPECT_EQ(list.exit_code, 2) << list.err;
}

// Without a Vulkan driver the message says what is missing and what to do; what needs no device runs.
TEST(CliCommandLine, NoDriverSaysWhatToDo) {
    test::TempDir dir;
    const std::string image = (dir / "i.exr").string();
    ASSERT_TRUE(write_image(image, Image(8, 8, {0.5f, 0.5f, 0.5f, 1})));
    const std::string none = "VK_DRIVER_FILES=" + (dir / "none.json").string() + " VK_ICD_FILENAMES= ";
    auto r = test::run(none + kdop("run --variant aabb-clip-n9 --current " + image + " --history " + image + " --out " +
                                   (dir / "o.exr").string()));
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("no Vulkan driver could be loaded"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("mesa-vulkan-drivers"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("VK_DRIVER_FILES"), std::string::npos) << r.err;
    auto flip = test::run(none + kdop("flip --cpu --reference " + image + " --test " + image));
    EXPECT_EQ(flip.exit_code, 0) << flip.err;
    auto fit = test::run(
        none + kdop("optimize --sphere --axes 3 --starts 1 --iterations 1 --out " + (dir / "s.axes").string()));
    EXPECT_EQ(fit.exit_code, 0) << fit.err;
}

} // namespace
} // namespace kdop
