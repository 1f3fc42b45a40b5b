#include "sequence/sequence.h"

#include "sequence/frame_checks.h"

#include "core/file_name.h"
#include "core/input_files.h"
#include "core/read_file.h"
#include "core/shown_text.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <initializer_list>
#include <string_view>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>

namespace kdop {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr std::uint32_t kMaxSide = 16384;

// "line L, column C" of byte `offset` (1-based, as nlohmann counts it) of `text`.
std::string position_of(std::string_view text, std::size_t offset) {
    offset = std::min(offset, text.size());
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i + 1 < offset; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return fmt::format("{}:{}", line, column);
}

// The reading of one sequence.json: errors name the file and the JSON path of the value.
class Reader {
public:
    explicit Reader(fs::path file) : file_(std::move(file)) {}
    const fs::path& path() const { return file_; }

    Error error(std::string_view where, std::string_view what) const {
        return {fmt::format("{}: {}: {}", file_.string(), where, what)};
    }

    // Refuses a key of `object` not in `allowed`: a misspelled key must not silently mean the default.
    Result<void> known_keys(const json& object, std::initializer_list<std::string_view> allowed,
                            std::string_view where) const {
        for (const auto& [key, value] : object.items())
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
                std::string known;
                for (std::string_view k : allowed) known += (known.empty() ? "" : ", ") + std::string(k);
                return std::unexpected(
                    error(where, fmt::format("unknown key \"{}\" (the keys here: {})", shown_text(key, 60), known)));
            }
        return {};
    }

    Result<std::uint32_t> side(const json& root, const char* key) const {
        const auto it = root.find(key);
        if (it == root.end() || !it->is_number_integer() || it->get<std::int64_t>() < 1 ||
            it->get<std::int64_t>() > kMaxSide)
            return std::unexpected(error(key, fmt::format("expected a whole number of pixels from 1 to {}", kMaxSide)));
        return std::uint32_t(it->get<std::int64_t>());
    }

    // One of `names` at `object[key]` (`fallback` when absent), as its index.
    Result<int> choice(const json& object, const char* key, std::initializer_list<const char*> names,
                       std::string_view where) const {
        const auto it = object.find(key);
        if (it == object.end()) return 0;
        std::string listed;
        for (const char* n : names) listed += fmt::format("{}\"{}\"", listed.empty() ? "" : " or ", n);
        if (it->is_string()) {
            int index = 0;
            for (const char* n : names) {
                if (it->get<std::string>() == n) return index;
                ++index;
            }
        }
        return std::unexpected(
            error(fmt::format("{}.{}", where, key),
                  fmt::format("{} is not a convention kdop knows; expected {}", shown_text(it->dump(), 60), listed)));
    }

    // "measure": ["ghosting"], ["shimmer"] or both, each once.
    Result<SequenceRoles> roles(const json& value) const {
        const Error wrong = error("measure", fmt::format("{} is not a list of the figures to measure; expected "
                                                         "[\"ghosting\"], [\"shimmer\"] or [\"ghosting\", \"shimmer\"]",
                                                         shown_text(value.dump(), 60)));
        if (!value.is_array() || value.empty()) return std::unexpected(wrong);
        SequenceRoles roles{false, false};
        for (const json& figure : value) {
            bool* role = !figure.is_string()                       ? nullptr
                         : figure.get<std::string>() == "ghosting" ? &roles.ghosting
                         : figure.get<std::string>() == "shimmer"  ? &roles.shimmer
                                                                   : nullptr;
            if (!role || *role) return std::unexpected(wrong); // unknown, or twice
            *role = true;
        }
        return roles;
    }

    // A file named relative to the sequence's folder: a regular file inside it.
    Result<fs::path> file(const fs::path& dir, const json& value, std::string_view where) const {
        if (!value.is_string() || value.get<std::string>().empty())
            return std::unexpected(error(where, "expected a file name relative to the sequence's folder"));
        const fs::path relative = value.get<std::string>();
        const std::string shown = shown_text(relative.string(), 200);
        if (relative.is_absolute())
            return std::unexpected(
                error(where, fmt::format("\"{}\" is absolute; name files relative to the sequence's folder", shown)));
        const fs::path path = dir / relative;
        // A path the kernel cannot take is refused as that, not as one outside the folder (which
        // is what its failed resolution would otherwise look like).
        if (path.native().size() >= PATH_MAX)
            return std::unexpected(
                error(where, fmt::format("\"{}\" makes a path of {} bytes with the sequence's folder; Linux opens no "
                                         "path of {} bytes or more (PATH_MAX)",
                                         shown, path.native().size(), PATH_MAX)));
        for (const fs::path& part : relative)
            if (part.native().size() > NAME_MAX)
                return std::unexpected(
                    error(where, fmt::format("\"{}\" holds a name of {} bytes; a file's name has at most {} (NAME_MAX)",
                                             shown, part.native().size(), NAME_MAX)));
        std::error_code ec;
        const fs::path resolved = fs::weakly_canonical(path, ec);
        if (ec)
            return std::unexpected(error(where, fmt::format("\"{}\": cannot be resolved: {}", shown, ec.message())));
        const fs::path inside = fs::weakly_canonical(dir, ec);
        if (ec || !lies_inside(resolved, inside))
            return std::unexpected(error(where, fmt::format("\"{}\" is outside the sequence's folder", shown)));
        // Shown as the folder and the name as written, escaped: a name is the file's text, and may
        // hold control bytes (found by tests/fuzz/sequence_fuzzer.cpp) or be any length.
        if (auto why = not_a_readable_file(path))
            return std::unexpected(
                error(where, fmt::format("{}: {}", terminal_text((dir / fs::path(shown)).string()), *why)));
        return path;
    }

private:
    fs::path file_;
};

} // namespace

const char* to_string(ColorRange range) { return range == ColorRange::hdr ? "hdr" : "ldr"; }

glm::vec2 canonical_motion(glm::vec2 stored, const MotionConvention& c, std::uint32_t width, std::uint32_t height) {
    glm::vec2 m = stored;
    if (c.units == MotionConvention::Units::uv) m *= glm::vec2(float(width), float(height));
    if (c.y_axis == MotionConvention::YAxis::up) m.y = -m.y;
    if (c.points_to == MotionConvention::PointsTo::current) m = -m;
    return m;
}

namespace {

// sequence.json's text as JSON, or an error naming the file and the position.
Result<json> parse_manifest(const std::string& text, const fs::path& path) {
    try {
        return json::parse(text);
    } catch (const json::parse_error& e) {
        // nlohmann's message, after its "[json.exception.parse_error.101] parse error at line 1,
        // column 2: " prefix, says what it found and expected.
        std::string_view what = e.what();
        if (const auto colon = what.find(": "); colon != std::string_view::npos) what.remove_prefix(colon + 2);
        return fail(
            fmt::format("{}:{}: not JSON: {}", path.string(), position_of(text, e.byte), shown_text(what, 200)));
    } catch (const json::exception& e) {
        // A number too large for a double ("99e9999", found by tests/fuzz/sequence_fuzzer.cpp) is
        // nlohmann's out_of_range, not a parse error, and has no position.
        return fail(fmt::format("{}: not JSON kdop can read: {}", path.string(), shown_text(e.what(), 200)));
    }
}

// The top level's version, size and settings (color, measure, motion, depth) into `s`.
Result<void> read_settings(const Reader& reader, const json& root, Sequence& s) {
    if (!root.is_object()) return fail(fmt::format("{}: expected a JSON object", reader.path().string()));
    if (auto ok = reader.known_keys(
            root, {"kdop_sequence", "width", "height", "output", "color", "measure", "motion", "depth", "frames"},
            "the top level");
        !ok)
        return ok;
    const auto version = root.find("kdop_sequence");
    if (version == root.end() || !version->is_number_integer())
        return std::unexpected(
            reader.error("kdop_sequence", fmt::format("expected the format's version, {}", kSequenceFormatVersion)));
    if (version->get<std::int64_t>() != kSequenceFormatVersion)
        return std::unexpected(
            reader.error("kdop_sequence", fmt::format("version {}; this kdop reads version {}",
                                                      version->get<std::int64_t>(), kSequenceFormatVersion)));
    auto width = reader.side(root, "width");
    if (!width) return std::unexpected(width.error());
    auto height = reader.side(root, "height");
    if (!height) return std::unexpected(height.error());
    s.width = *width;
    s.height = *height;

    if (const auto output = root.find("output"); output != root.end()) {
        if (!output->is_object()) return std::unexpected(reader.error("output", "expected an object"));
        if (auto ok = reader.known_keys(*output, {"width", "height"}, "output"); !ok) return ok;
        auto output_width = reader.side(*output, "width");
        if (!output_width) return std::unexpected(output_width.error());
        auto output_height = reader.side(*output, "height");
        if (!output_height) return std::unexpected(output_height.error());
        // An upscaler's output is at least its input on each side (FSR 2's and NSS's ratios are >= 1).
        if (*output_width < s.width || *output_height < s.height)
            return std::unexpected(reader.error(
                "output", fmt::format("{}x{} is smaller than the frames' {}x{}; the output of an upscaling resolve "
                                      "is at least its input on each side",
                                      *output_width, *output_height, s.width, s.height)));
        s.output_width = *output_width;
        s.output_height = *output_height;
    }

    if (const auto color = root.find("color"); color != root.end()) {
        if (!color->is_object()) return std::unexpected(reader.error("color", "expected an object"));
        if (auto ok = reader.known_keys(*color, {"range"}, "color"); !ok) return ok;
        auto range = reader.choice(*color, "range", {"ldr", "hdr"}, "color");
        if (!range) return std::unexpected(range.error());
        s.color_range = ColorRange(*range);
    }

    if (const auto measure = root.find("measure"); measure != root.end()) {
        auto roles = reader.roles(*measure);
        if (!roles) return std::unexpected(roles.error());
        s.measure = *roles;
    }

    if (const auto motion = root.find("motion"); motion != root.end()) {
        if (!motion->is_object()) return std::unexpected(reader.error("motion", "expected an object"));
        if (auto ok = reader.known_keys(*motion, {"units", "points_to", "y_axis"}, "motion"); !ok) return ok;
        auto units = reader.choice(*motion, "units", {"pixels", "uv"}, "motion");
        auto points_to = reader.choice(*motion, "points_to", {"previous", "current"}, "motion");
        auto y_axis = reader.choice(*motion, "y_axis", {"down", "up"}, "motion");
        for (const auto* r : {&units, &points_to, &y_axis})
            if (!*r) return std::unexpected(r->error());
        s.motion = {MotionConvention::Units(*units), MotionConvention::PointsTo(*points_to),
                    MotionConvention::YAxis(*y_axis)};
    }

    if (const auto depth = root.find("depth"); depth != root.end()) {
        if (!depth->is_object()) return std::unexpected(reader.error("depth", "expected an object"));
        if (auto ok = reader.known_keys(*depth, {"nearer"}, "depth"); !ok) return ok;
        auto nearer = reader.choice(*depth, "nearer", {"smaller", "larger"}, "depth");
        if (!nearer) return std::unexpected(nearer.error());
        s.depth_nearer_larger = *nearer == 1;
    }
    return {};
}

// frames[i]: its files, camera cut and jitter.
Result<SequenceFrame> read_frame(const Reader& reader, const fs::path& dir, const json& f, std::size_t i) {
    const std::string where = fmt::format("frames[{}]", i);
    if (!f.is_object()) return std::unexpected(reader.error(where, "expected an object"));
    if (auto ok = reader.known_keys(f, {"color", "motion", "depth", "reference", "jitter", "camera_cut"}, where); !ok)
        return std::unexpected(ok.error());
    SequenceFrame frame;
    if (const auto cut = f.find("camera_cut"); cut != f.end()) {
        if (!cut->is_boolean()) return std::unexpected(reader.error(where + ".camera_cut", "expected true or false"));
        frame.camera_cut = cut->get<bool>();
    }
    if (!f.contains("color")) return std::unexpected(reader.error(where, "has no \"color\" file"));
    auto color = reader.file(dir, f["color"], where + ".color");
    if (!color) return std::unexpected(color.error());
    frame.color = *color;
    if (f.contains("motion")) {
        auto motion = reader.file(dir, f["motion"], where + ".motion");
        if (!motion) return std::unexpected(motion.error());
        frame.motion = *motion;
    } else if (i > 0 && !frame.camera_cut) {
        return std::unexpected(
            reader.error(where, "has no \"motion\" file, which every frame with a history needs (all but the "
                                "first and the camera cuts)"));
    }
    for (auto [key, target] : {std::pair{"depth", &frame.depth}, std::pair{"reference", &frame.reference}})
        if (f.contains(key)) {
            auto file = reader.file(dir, f[key], where + "." + key);
            if (!file) return std::unexpected(file.error());
            *target = *file;
        }
    if (const auto jitter = f.find("jitter"); jitter != f.end()) {
        const bool pair =
            jitter->is_array() && jitter->size() == 2 && (*jitter)[0].is_number() && (*jitter)[1].is_number();
        // As doubles first: a float conversion of 1e300 would be undefined.
        const double x = pair ? (*jitter)[0].get<double>() : NAN, y = pair ? (*jitter)[1].get<double>() : NAN;
        if (!(std::abs(x) <= 0.5 && std::abs(y) <= 0.5))
            return std::unexpected(
                reader.error(where + ".jitter", fmt::format("{} is not [x, y] within half a pixel ([-0.5, 0.5] each)",
                                                            shown_text(jitter->dump(), 60))));
        frame.jitter = glm::vec2(float(x), float(y));
    }
    return frame;
}

} // namespace

Result<Sequence> read_sequence(const fs::path& dir) {
    const fs::path path = dir / "sequence.json";
    auto text = read_input_file(path);
    if (!text) return std::unexpected(text.error());
    // Rows, charts, frames and pictures are named after the folder: refused here, before any work,
    // where the name could not name them (core/file_name.h).
    const std::string name = fs::weakly_canonical(dir).filename().string();
    if (auto problem = name_problem(name))
        return usage_fail(fmt::format("{}: the folder's name {}; kdop names the sequence's outputs after it, so rename "
                                      "the folder",
                                      shown_text(dir.string(), 300), *problem));
    auto root = parse_manifest(*text, path);
    if (!root) return std::unexpected(root.error());
    const Reader reader(path);
    Sequence s;
    s.dir = dir;
    s.name = name;
    if (auto ok = read_settings(reader, *root, s); !ok) return std::unexpected(ok.error());
    const auto frames = root->find("frames");
    if (frames == root->end() || !frames->is_array() || frames->empty())
        return std::unexpected(reader.error("frames", "expected a list of at least one frame"));
    for (std::size_t i = 0; i < frames->size(); ++i) {
        auto frame = read_frame(reader, dir, (*frames)[i], i);
        if (!frame) return std::unexpected(frame.error());
        if (s.upscales() && frame->reference.empty())
            return std::unexpected(reader.error(
                fmt::format("frames[{}]", i),
                "has no \"reference\" file, which every frame of an upscaled sequence needs: its outputs are "
                "measured against the reference at the output size"));
        s.frames.push_back(std::move(*frame));
    }
    // Every file named is an input from here on, read yet or not (a depth file the resolve never
    // reads included): an output that would replace one is refused, and an earlier run's listing
    // never removes one (core/input_files.h, core/output_listing.h).
    for (const SequenceFrame& frame : s.frames)
        for (const fs::path* file : {&frame.color, &frame.motion, &frame.depth, &frame.reference})
            if (!file->empty()) note_input(*file);
    // The declared size against the first frame's header (no pixel read): a sequence.json that says
    // 8192x8192 over 32x16 frames would otherwise size every buffer of a run for frames it never has.
    const fs::path& first = s.frames.front().color;
    auto size = read_image_size(first.string());
    if (!size) return std::unexpected(size.error());
    if (size->x != s.width || size->y != s.height)
        return fail(fmt::format("{}: {}x{}, but {} says {}x{}", first.string(), size->x, size->y,
                                (s.dir / "sequence.json").string(), s.width, s.height));
    return s;
}

Result<void> check_outside(const Sequence& s, const fs::path& out, std::string_view option) {
    std::error_code ec;
    const fs::path folder = fs::weakly_canonical(out, ec);
    if (ec) return {}; // an --out that cannot be resolved is refused as that where it is prepared
    std::vector<fs::path> files{s.dir / "sequence.json"};
    for (const SequenceFrame& frame : s.frames)
        for (const fs::path* file : {&frame.color, &frame.motion, &frame.depth, &frame.reference})
            if (!file->empty()) files.push_back(*file);
    for (const fs::path& file : files) {
        const fs::path real = fs::canonical(file, ec);
        if (!ec && lies_inside(real, folder))
            return usage_fail(fmt::format("{} {}: holds {}, a file of the sequence {}; kdop writes this run's outputs "
                                          "there and never over an input, so give a folder outside the sequence's "
                                          "files",
                                          option, out.string(), file.string(), s.dir.string()));
    }
    return {};
}

namespace {

// The size a frame's files have: the sequence's, a reference of an upscaled sequence the output's.
glm::uvec2 frame_size(const Sequence& s) { return {s.width, s.height}; }
glm::uvec2 reference_size(const Sequence& s) {
    return s.upscales() ? glm::uvec2(s.output_width, s.output_height) : frame_size(s);
}

// Refuses a file of another size than `expected`.
Result<void> check_size(glm::uvec2 size, glm::uvec2 expected, const fs::path& file, const Sequence& s) {
    if (size == expected) return {};
    return fail(fmt::format("{}: {}x{}, but the sequence{} is {}x{} ({})", file.string(), size.x, size.y,
                            expected == frame_size(s) ? "" : "'s output", expected.x, expected.y,
                            (s.dir / "sequence.json").string()));
}

// A frame's file, open: read_sequence checked that it lies inside the folder, but the file may since
// have been replaced by a link to ../secret.exr. So it is opened first (never blocking on a FIFO),
// and what was opened, found through /proc/self/fd, must be a regular file inside the folder; the
// image is then read through the descriptor, so no path is resolved again. A link that stays inside
// is followed, as read_sequence follows it.
class FrameFile {
public:
    static Result<FrameFile> open(const fs::path& file, const Sequence& s) {
        FrameFile f;
        f.fd_ = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        if (f.fd_ < 0) return fail(fmt::format("{}: cannot open: {}", file.string(), std::strerror(errno)));
        struct stat st {};
        if (fstat(f.fd_, &st) != 0 || !S_ISREG(st.st_mode))
            return fail(fmt::format("{}: is no longer a regular file", file.string()));
        std::error_code ec;
        const fs::path opened = fs::read_symlink(f.proc_path(), ec), folder = fs::canonical(s.dir, ec);
        if (ec || !lies_inside(opened, folder))
            return fail(fmt::format("{}: now leads outside the sequence's folder {} (to {}); kdop reads only the "
                                    "files inside it",
                                    file.string(), folder.string(), opened.string()));
        return f;
    }
    FrameFile(FrameFile&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
    FrameFile& operator=(FrameFile&&) = delete;
    ~FrameFile() {
        if (fd_ >= 0) ::close(fd_);
    }
    std::string proc_path() const { return fmt::format("/proc/self/fd/{}", fd_); }

private:
    FrameFile() = default;
    int fd_ = -1;
};

// Frame file `file`, opened, its size checked on its header before any pixel is decoded (a frame
// that claims 16384x16384 in a 64x36 sequence is refused for that, not read), then read through
// the descriptor by `read`.
Result<Image> read_frame_file(const fs::path& file, const Sequence& s, glm::uvec2 expected, const auto& read) {
    auto opened = FrameFile::open(file, s);
    if (!opened) return std::unexpected(opened.error());
    auto size = read_image_size(opened->proc_path(), file.string());
    if (!size) return std::unexpected(size.error());
    if (auto ok = check_size(*size, expected, file, s); !ok) return std::unexpected(ok.error());
    return read(opened->proc_path());
}

Result<Image> read_color(const fs::path& file, const Sequence& s, InputSpace space, std::string_view what,
                         glm::uvec2 expected) {
    auto image = read_frame_file(file, s, expected,
                                 [&](const std::string& fd) { return read_image(fd, 0, space, file.string()); });
    if (!image) return image;
    if (auto ok = check_finite(*image, file, 3, what); !ok) return std::unexpected(ok.error());
    return image;
}

// A data file (motion, depth) of `channels` channels, each value finite.
Result<Image> read_data(const fs::path& file, const Sequence& s, int channels, std::string_view what) {
    auto image = read_frame_file(file, s, frame_size(s),
                                 [&](const std::string& fd) { return read_data_image(fd, channels, file.string()); });
    if (!image) return image;
    if (auto ok = check_finite(*image, file, channels, what); !ok) return std::unexpected(ok.error());
    return image;
}

} // namespace

Result<Image> load_frame_color(const Sequence& s, std::size_t index, InputSpace space) {
    return read_color(s.frames.at(index).color, s, space, "color", frame_size(s));
}

Result<LoadedFrame> load_frame(const Sequence& s, std::size_t index, InputSpace space, bool depth) {
    const SequenceFrame& f = s.frames.at(index);
    LoadedFrame out;
    auto color = read_color(f.color, s, space, "color", frame_size(s));
    if (!color) return std::unexpected(color.error());
    out.color = std::move(*color);
    out.jitter = s.frames[index].jitter.value_or(glm::vec2(0.0f));
    if (!s.starts_history(index)) {
        auto motion = read_data(f.motion, s, 2, "motion");
        if (!motion) return std::unexpected(motion.error());
        out.motion.reserve(motion->pixels.size());
        for (const glm::vec4& m : motion->pixels)
            out.motion.push_back(canonical_motion(glm::vec2(m), s.motion, s.width, s.height));
    }
    if (depth && !f.depth.empty()) {
        auto image = read_data(f.depth, s, 1, "depth");
        if (!image) return std::unexpected(image.error());
        out.depth = std::move(*image);
    }
    if (!f.reference.empty()) {
        auto reference = read_color(f.reference, s, space, "the reference", reference_size(s));
        if (!reference) return std::unexpected(reference.error());
        out.reference = std::move(*reference);
    }
    return out;
}

} // namespace kdop
