#include "sequence/nss_capture.h"

#include "sequence/frame_checks.h"

#include "core/file_name.h"
#include "core/input_files.h"
#include "core/read_file.h"
#include "core/shown_text.h"
#include "images/image_io.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

// Evidence below is cited from arm/neural-graphics-model-gym at ef328bf ("Reduce NSS v1 recurrent
// output memory"): READER is scripts/safetensors_generator/dataset_readers/nss_exr_dataset_reader.py,
// SPEC docs/nss/nss_dataset_specification.md.

namespace kdop {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr std::uint32_t kMaxSide = 16384;
constexpr std::string_view kNonFinite = "\x01non-finite:"; // what a NaN or Infinity literal becomes

// Arm's JSON loader (SafetensorsFeatureIterator.load_metadata) takes the unquoted literals NaN,
// Infinity and -Infinity (what Python's json module writes for them); nlohmann refuses them. Each
// outside a string becomes a string marked kNonFinite, so that where a number is expected it is
// refused as not finite, naming the field, rather than as JSON that cannot be read.
std::string with_non_finite_as_strings(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            out += c;
            if (c == '\\' && i + 1 < text.size())
                out += text[++i];
            else if (c == '"')
                in_string = false;
            continue;
        }
        if (c == '"') {
            in_string = true;
            out += c;
            continue;
        }
        bool replaced = false;
        for (std::string_view literal : {"-Infinity", "Infinity", "-NaN", "NaN", "-inf", "inf", "-nan", "nan"})
            if (text.substr(i, literal.size()) == literal) {
                out += fmt::format("\"\\u0001non-finite:{}\"", literal); // kNonFinite, escaped
                i += literal.size() - 1;
                replaced = true;
                break;
            }
        if (!replaced) out += c;
    }
    return out;
}

// The reading of NNNN.json: errors name the file and the JSON path of the value.
class JsonReader {
public:
    explicit JsonReader(fs::path file) : file_(std::move(file)) {}
    const fs::path& file() const { return file_; }

    Error error(std::string_view where, std::string_view what) const {
        return {fmt::format("{}: {}: {}", file_.string(), where, what)};
    }

    Result<const json*> member(const json& object, const char* key, std::string_view where) const {
        const auto it = object.find(key);
        if (it == object.end())
            return std::unexpected(error(where, fmt::format("has no \"{}\", which kdop reads", key)));
        return &*it;
    }

    // A finite number at `value`.
    Result<double> number(const json& value, std::string_view where) const {
        if (value.is_string() && value.get<std::string>().starts_with(kNonFinite))
            return std::unexpected(error(where, fmt::format("is {}; it must be a finite number",
                                                            value.get<std::string>().substr(kNonFinite.size()))));
        if (!value.is_number())
            return std::unexpected(error(where, fmt::format("{} is not a number", shown_text(value.dump(), 60))));
        return value.get<double>();
    }

    Result<std::uint32_t> side(const json& object, const char* key, std::string_view where) const {
        auto value = member(object, key, where);
        if (!value) return std::unexpected(value.error());
        if (!(*value)->is_number_integer() || (*value)->get<std::int64_t>() < 1 ||
            (*value)->get<std::int64_t>() > kMaxSide)
            return std::unexpected(
                error(fmt::format("{}.{}", where, key), fmt::format("{} is not a whole number of pixels from 1 to {}",
                                                                    shown_text((*value)->dump(), 60), kMaxSide)));
        return std::uint32_t((*value)->get<std::int64_t>());
    }

private:
    fs::path file_;
};

// The .exr files of `dir`, sorted by name: READER pairs the streams' files with each other and
// with the JSON's frames by their position in this order (safetensors_feature_iterator.py
// make_image_dict, `sorted(... .rglob("*.exr"))`, and READER `self.metadata["Frames"][self.count]`),
// never by a number in the name. kdop lists the folder itself, not its subfolders.
Result<std::vector<fs::path>> exr_files(const fs::path& dir, std::string_view what) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        return fail(fmt::format("{}: missing; an NSS capture holds its {} there", dir.string(), what));
    std::vector<fs::path> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec))
        if (entry.path().extension() == ".exr" && entry.is_regular_file(ec)) files.push_back(entry.path());
    if (ec) return fail(fmt::format("{}: cannot be listed: {}", dir.string(), ec.message()));
    if (files.empty())
        return fail(fmt::format("{}: holds no .exr file; an NSS capture holds its {} there", dir.string(), what));
    std::sort(files.begin(), files.end());
    return files;
}

// Refuses a file whose header is not `width` x `height`.
Result<void> check_size(const fs::path& file, std::uint32_t width, std::uint32_t height, std::string_view why) {
    auto size = read_image_size(file.string());
    if (!size) return std::unexpected(size.error());
    if (size->x != width || size->y != height)
        return fail(fmt::format("{}: {}x{}, but {} is {}x{}", file.string(), size->x, size->y, why, width, height));
    return {};
}

// Under --nss-range ldr: refuses a color value outside [0, 1] (after the exposure), naming the file
// and the pixel, never clamping it, as kdop refuses an LDR sequence's (temporal/taa_measure.cpp).
Result<void> check_unit_range(const Image& image, const fs::path& file, float exposure) {
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (const float v = image.pixels[i][c]; !(v >= 0.0f && v <= 1.0f))
                return fail(fmt::format("{}: pixel ({}, {}) has {} {}{}, outside [0, 1]; --nss-range ldr measures the "
                                        "capture in LDR-FLIP, which takes linear values from 0 to 1: read an HDR "
                                        "capture with --nss-range hdr (kdop does not clamp it)",
                                        file.string(), i % image.width, i / image.width, "RGB"[c], v,
                                        exposure == 1.0f ? "" : fmt::format(" (times the Exposure {})", exposure)));
    return {};
}

} // namespace

Result<std::string> nss_ratio_folder(double ratio, std::string_view option) {
    if (!(ratio >= 1.0 && ratio <= 8.0))
        return usage_fail(fmt::format("{} {}: an NSS upscaling ratio is from 1 to 8 (x2, x1_5, ...)", option, ratio));
    // One decimal at most: Arm's name drops "_0" wherever it occurs, so 1.05 would be "x15".
    const double tenths = std::round(ratio * 10.0);
    if (std::abs(ratio * 10.0 - tenths) > 1e-9)
        return usage_fail(fmt::format("{} {}: NSS names a ratio's folder with one decimal at most (x2, x1_5, "
                                      "x1_7, x1_3)",
                                      option, ratio));
    const int whole = int(tenths) / 10, tenth = int(tenths) % 10;
    return tenth == 0 ? fmt::format("x{}", whole) : fmt::format("x{}_{}", whole, tenth);
}

namespace {

// TargetResolution, Samples and ReverseZ into `c`; the ratio's index into each frame's
// NormalizedPerRatioJitter (READER line 267).
Result<std::size_t> read_capture_settings(const JsonReader& reader, const json& root_json, const fs::path& path,
                                          const std::string& index_key, double ratio, NssCapture& c) {
    auto target = reader.member(root_json, "TargetResolution", "the top level");
    if (!target) return std::unexpected(target.error());
    if (!(*target)->is_object())
        return std::unexpected(reader.error("TargetResolution", "expected {\"X\": width, \"Y\": height}"));
    auto width = reader.side(**target, "X", "TargetResolution");
    if (!width) return std::unexpected(width.error());
    auto height = reader.side(**target, "Y", "TargetResolution");
    if (!height) return std::unexpected(height.error());
    c.width = *width, c.height = *height;

    // Samples: read by READER for its Count only, which kdop does not use; checked to be an object.
    if (const auto samples = root_json.find("Samples"); samples != root_json.end() && !samples->is_object())
        return std::unexpected(reader.error("Samples", "expected an object ({\"Sequence\", \"Count\", ...})"));

    // ReverseZ: READER `if reverse_z: depth_raw = 1.0 - depth_raw` (line 196), absent meaning false
    // (line 190, `.get("ReverseZ", False)`); so does kdop, and its depth is then always forward
    // (smaller is nearer), as the rest of READER assumes ("forward order normalised").
    if (const auto reverse = root_json.find("ReverseZ"); reverse != root_json.end()) {
        if (!reverse->is_boolean()) return std::unexpected(reader.error("ReverseZ", "expected true or false"));
        c.reverse_z = reverse->get<bool>();
    }

    auto indices = reader.member(root_json, "UpscalingRatiosIndices", "the top level");
    if (!indices) return std::unexpected(indices.error());
    if (!(*indices)->is_object())
        return std::unexpected(reader.error("UpscalingRatiosIndices", "expected an object such as {\"x2_index\": 0}"));
    const auto index_it = (*indices)->find(index_key);
    if (index_it == (*indices)->end())
        return fail(fmt::format("{}: UpscalingRatiosIndices has no \"{}\": the capture has no jitter for ratio {} "
                                "(--ratio {})",
                                path.string(), index_key, ratio, ratio));
    if (!index_it->is_number_unsigned())
        return std::unexpected(reader.error("UpscalingRatiosIndices." + index_key, "expected an index from 0"));
    return index_it->get<std::size_t>();
}

// The files of the streams kdop reads, one per frame, paired by sorted name.
struct Stream {
    fs::path dir;
    const char* what;
    std::vector<fs::path> files;
};
using Streams = std::array<Stream, 4>; // input color, depth and motion, then the reference

Result<Streams> capture_streams(const fs::path& root, const std::string& folder, const std::string& sequence,
                                double ratio, std::size_t listed, const fs::path& path) {
    // The streams kdop reads. motion_gt, which READER requires too, is not: kdop's resolve
    // reprojects with the input's motion.
    const fs::path ratio_dir = root / folder;
    if (std::error_code ec; !fs::is_directory(ratio_dir, ec))
        return fail(fmt::format("{}: missing; the capture has no frames at ratio {} (--ratio {})", ratio_dir.string(),
                                ratio, ratio));
    Streams streams{{{ratio_dir / "color" / sequence, "input color", {}},
                     {ratio_dir / "depth" / sequence, "input depth", {}},
                     {ratio_dir / "motion" / sequence, "input motion", {}},
                     {root / "ground_truth" / sequence, "reference (ground truth)", {}}}};
    for (Stream& s : streams) {
        auto files = exr_files(s.dir, s.what);
        if (!files) return std::unexpected(files.error());
        s.files = std::move(*files);
    }
    // READER writes min(counts) frames and says nothing of the rest (line 102). kdop refuses streams
    // of different counts instead (a frame missing from one would pair every later file with the
    // wrong frame), and JSON that lists fewer frames than the files, where READER would fail on an
    // index. JSON that lists more frames than the files is READER's own test fixture (100 frames,
    // one file each): the files' count is the capture's.
    const std::size_t count = streams[0].files.size();
    for (const Stream& s : streams)
        if (s.files.size() != count)
            return fail(fmt::format("{}: {} frames, but {} holds {}; every stream of an NSS capture holds one file "
                                    "per frame, paired by sorted name",
                                    s.dir.string(), s.files.size(), streams[0].dir.string(), count));
    if (listed < count)
        return fail(fmt::format("{}: Frames lists {} frames, but {} holds {} files", path.string(), listed,
                                streams[0].dir.string(), count));
    return streams;
}

// The reference's size against TargetResolution, the input's against it over the ratio, into `c`.
Result<void> check_capture_sizes(const Streams& streams, double ratio, const fs::path& path, NssCapture& c) {
    // Sizes: the reference at TargetResolution; the input at TargetResolution / ratio, rounded down
    // (the capture guide's `int(TargetResolution / Ratio)`) or to the nearest (the model's
    // `round(input * scale)`): the spec writes `1920/ratio` and says neither, so kdop takes either.
    if (auto ok = check_size(streams[3].files.front(), c.width, c.height,
                             fmt::format("TargetResolution in {}", path.string()));
        !ok)
        return std::unexpected(ok.error());
    auto input = read_image_size(streams[0].files.front().string());
    if (!input) return std::unexpected(input.error());
    auto fits = [&](std::uint32_t in, std::uint32_t target) {
        const double exact = double(target) / ratio;
        return in == std::uint32_t(std::floor(exact)) || in == std::uint32_t(std::lround(exact));
    };
    if (!fits(input->x, c.width) || !fits(input->y, c.height))
        return fail(fmt::format("{}: {}x{}, but ratio {} of TargetResolution {}x{} ({}) is {}x{} (rounded down or to "
                                "the nearest)",
                                streams[0].files.front().string(), input->x, input->y, ratio, c.width, c.height,
                                path.string(), std::lround(c.width / ratio), std::lround(c.height / ratio)));
    c.input_width = input->x, c.input_height = input->y;
    for (int s : {1, 2})
        if (auto ok = check_size(streams[s].files.front(), c.input_width, c.input_height,
                                 fmt::format("the input color {}", streams[0].files.front().string()));
            !ok)
            return std::unexpected(ok.error());

    return {};
}

// Frames[i]'s camera cut, exposure and jitter into `frame`.
Result<void> read_capture_frame(const JsonReader& reader, const json& f, std::size_t i, std::size_t ratio_index,
                                const std::string& index_key, const NssCapture& c, NssFrame& frame) {
    const std::string where = fmt::format("Frames[{}]", i);
    if (!f.is_object()) return std::unexpected(reader.error(where, "expected an object"));
    // CameraCut: "true when the current frame is the first frame after a camera cut" (SPEC); absent
    // means false (READER line 253). kdop drops the history there.
    if (const auto cut = f.find("CameraCut"); cut != f.end()) {
        if (!cut->is_boolean()) return std::unexpected(reader.error(where + ".CameraCut", "expected true or false"));
        frame.camera_cut = cut->get<bool>();
    }
    // Exposure: optional; READER keeps ln(Exposure) (line 263) and the training multiplies color
    // and ground truth alike by exp of it before tone mapping (src/ng_model_gym/usecases/nss/data/
    // process_functions.py lines 125-126): the files are not pre-exposed. kdop multiplies both by
    // it as it reads them, so HDR-FLIP measures what the model is trained on; both alike, so the
    // resolve and the reference stay in the same units. Absent: 1.
    if (const auto exposure = f.find("Exposure"); exposure != f.end()) {
        auto value = reader.number(*exposure, where + ".Exposure");
        if (!value) return std::unexpected(value.error());
        if (!(*value > 0.0) || !std::isfinite(float(*value)))
            return std::unexpected(
                reader.error(where + ".Exposure", fmt::format("{} is not a positive multiplier", *value)));
        frame.exposure = float(*value);
    }
    // Jitter: NormalizedPerRatioJitter[index] is the sample's offset from the pixel's center
    // divided by the input size (SPEC, "Per-frame"); READER multiplies it by the color file's
    // size (line 281) with no change of sign, and the model samples pixel i at i + 0.5 + jitter
    // (src/ng_model_gym/core/model/graphics_utils.py line 265), y down: kdop's convention, so
    // it is only scaled. READER falls back to the old key QuantisedPerRatioJitter, and so does kdop.
    const char* jitter_key = f.contains("NormalizedPerRatioJitter")  ? "NormalizedPerRatioJitter"
                             : f.contains("QuantisedPerRatioJitter") ? "QuantisedPerRatioJitter"
                                                                     : nullptr;
    if (!jitter_key)
        return std::unexpected(reader.error(where, "has no \"NormalizedPerRatioJitter\", which kdop reads"));
    const json& list = f[jitter_key];
    const std::string jitter_where = fmt::format("{}.{}[{}]", where, jitter_key, ratio_index);
    if (!list.is_array() || ratio_index >= list.size())
        return std::unexpected(reader.error(
            jitter_where, fmt::format("missing: UpscalingRatiosIndices.{} is {}", index_key, ratio_index)));
    const json& j = list[ratio_index];
    if (!j.is_object() || !j.contains("X") || !j.contains("Y"))
        return std::unexpected(reader.error(jitter_where, "expected {\"X\": x, \"Y\": y}"));
    auto x = reader.number(j["X"], jitter_where + ".X");
    if (!x) return std::unexpected(x.error());
    auto y = reader.number(j["Y"], jitter_where + ".Y");
    if (!y) return std::unexpected(y.error());
    frame.jitter = glm::vec2(float(*x * c.input_width), float(*y * c.input_height));
    // Within half an input pixel (SPEC: "the Jitter {-0.5, 0.5} divided by the SrcRes"), to
    // float's rounding of the product.
    if (!(std::abs(frame.jitter.x) <= 0.5001f && std::abs(frame.jitter.y) <= 0.5001f))
        return std::unexpected(
            reader.error(jitter_where, fmt::format("({}, {}) is ({}, {}) input pixels, beyond half a pixel", *x, *y,
                                                   frame.jitter.x, frame.jitter.y)));
    return {};
}

} // namespace

Result<NssCapture> read_nss_capture(const fs::path& root, const std::string& sequence, double ratio) {
    auto folder = nss_ratio_folder(ratio);
    if (!folder) return std::unexpected(folder.error());
    if (auto problem = name_problem(sequence))
        return usage_fail(fmt::format("--nss-sequence {}: the name {}; kdop names the sequence's outputs after it",
                                      shown_text(sequence, 60), *problem));
    const fs::path path = root / (sequence + ".json");
    auto text = read_input_file(path);
    if (!text) return std::unexpected(text.error());
    json root_json;
    try {
        root_json = json::parse(with_non_finite_as_strings(*text));
    } catch (const json::exception& e) {
        return fail(fmt::format("{}: not JSON kdop can read: {}", path.string(), shown_text(e.what(), 200)));
    }
    const JsonReader reader(path);
    if (!root_json.is_object()) return fail(fmt::format("{}: expected a JSON object", path.string()));

    NssCapture c;
    c.root = root;
    c.sequence = sequence;
    c.ratio_folder = *folder;
    const std::string index_key = fmt::format("{}_index", *folder);
    auto ratio_index = read_capture_settings(reader, root_json, path, index_key, ratio, c);
    if (!ratio_index) return std::unexpected(ratio_index.error());
    auto frames_json = reader.member(root_json, "Frames", "the top level");
    if (!frames_json) return std::unexpected(frames_json.error());
    if (!(*frames_json)->is_array() || (*frames_json)->empty())
        return std::unexpected(reader.error("Frames", "expected a list of at least one frame"));
    auto streams = capture_streams(root, *folder, sequence, ratio, (*frames_json)->size(), path);
    if (!streams) return std::unexpected(streams.error());
    if (auto ok = check_capture_sizes(*streams, ratio, path, c); !ok) return std::unexpected(ok.error());
    for (std::size_t i = 0; i < (*streams)[0].files.size(); ++i) {
        NssFrame frame{(*streams)[0].files[i], (*streams)[1].files[i], (*streams)[2].files[i], (*streams)[3].files[i]};
        if (auto ok = read_capture_frame(reader, (**frames_json)[i], i, *ratio_index, index_key, c, frame); !ok)
            return std::unexpected(ok.error());
        c.frames.push_back(std::move(frame));
    }
    for (const NssFrame& f : c.frames)
        for (const fs::path* file : {&f.color, &f.depth, &f.motion, &f.reference}) note_input(*file);
    note_input(path);
    return c;
}

Result<void> check_outside(const NssCapture& c, const fs::path& out, std::string_view option) {
    std::error_code ec;
    const fs::path folder = fs::weakly_canonical(out, ec);
    if (ec) return {};
    std::vector<fs::path> files{c.root / (c.sequence + ".json")};
    for (const NssFrame& f : c.frames)
        for (const fs::path* file : {&f.color, &f.depth, &f.motion, &f.reference}) files.push_back(*file);
    for (const fs::path& file : files) {
        const fs::path real = fs::canonical(file, ec);
        if (!ec && lies_inside(real, folder))
            return usage_fail(fmt::format("{} {}: holds {}, a file of the NSS capture {}; kdop writes this run's "
                                          "outputs there and never over an input, so give a folder outside it",
                                          option, out.string(), file.string(), c.root.string()));
    }
    return {};
}

std::string NssFrames::frame_label(std::size_t index) const {
    return fmt::format("{} (frame {})", c_.frames[index].color.string(), index);
}

Result<LoadedFrame> NssFrames::frame(std::size_t index) const {
    const NssFrame& f = c_.frames.at(index);
    LoadedFrame out;
    // Color and reference: linear HDR (SPEC "Images"), RGB by name, alpha ignored (READER reads
    // channels "RGB"); multiplied by the frame's exposure (see read_nss_capture).
    auto read_color = [&](const fs::path& file, std::uint32_t width, std::uint32_t height,
                          std::string_view what) -> Result<Image> {
        if (auto ok = check_size(file, width, height, fmt::format("{}", what == "color" ? "the input" : "the output"));
            !ok)
            return std::unexpected(ok.error());
        auto image = read_image(file.string(), 0, InputSpace::linear);
        if (!image) return image;
        if (auto ok = check_finite(*image, file, 3, what); !ok) return std::unexpected(ok.error());
        for (glm::vec4& p : image->pixels) p = glm::vec4(glm::vec3(p) * f.exposure, 1.0f);
        if (range_ == ColorRange::ldr)
            if (auto ok = check_unit_range(*image, file, f.exposure); !ok) return std::unexpected(ok.error());
        return image;
    };
    auto read_data = [&](const fs::path& file, int channels, std::string_view what) -> Result<Image> {
        if (auto ok = check_size(file, c_.input_width, c_.input_height, "the input"); !ok)
            return std::unexpected(ok.error());
        auto image = read_data_image(file.string(), channels);
        if (!image) return image;
        if (auto ok = check_finite(*image, file, channels, what); !ok) return std::unexpected(ok.error());
        return image;
    };
    auto color = read_color(f.color, c_.input_width, c_.input_height, "color");
    if (!color) return std::unexpected(color.error());
    out.color = std::move(*color);
    out.jitter = f.jitter;
    if (!starts_history(index)) {
        // Motion: R, G = the surface's UV now minus its UV in the previous frame, in units of the
        // file's own width and height, v down: READER clamps it to [-1, 1] and scales it by the
        // file's size (lines 175-184) with no change of sign, and the model's shaders reproject to
        // `uv - motion` (src/ng_model_gym/usecases/nss/model/shaders/nss_v1/pre_process.slang line
        // 943). kdop's motion points to the previous position, in input pixels: clamped as READER
        // does, scaled by the file's size and negated (canonical_motion's uv, points-to-current).
        auto motion = read_data(f.motion, 2, "motion");
        if (!motion) return std::unexpected(motion.error());
        const MotionConvention nss{MotionConvention::Units::uv, MotionConvention::PointsTo::current,
                                   MotionConvention::YAxis::down};
        out.motion.reserve(motion->pixels.size());
        for (const glm::vec4& m : motion->pixels)
            out.motion.push_back(canonical_motion(glm::clamp(glm::vec2(m), glm::vec2(-1.0f), glm::vec2(1.0f)), nss,
                                                  c_.input_width, c_.input_height));
    }
    if (depth_) {
        // Depth: R (READER reads channel "R"), device depth; reversed to forward (smaller is
        // nearer) where ReverseZ says, as READER does (1 - depth).
        auto depth = read_data(f.depth, 1, "depth");
        if (!depth) return std::unexpected(depth.error());
        if (c_.reverse_z)
            for (glm::vec4& p : depth->pixels) p.x = 1.0f - p.x;
        out.depth = std::move(*depth);
    }
    auto reference = read_color(f.reference, c_.width, c_.height, "the reference");
    if (!reference) return std::unexpected(reference.error());
    out.reference = std::move(*reference);
    return out;
}

} // namespace kdop
