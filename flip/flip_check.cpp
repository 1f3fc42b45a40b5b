#include "flip/flip_check.h"

#include "flip/flip.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace kdop {

const std::string& output_path(const FlipRunOptions& o, FlipOutput output) {
    switch (output) {
    case FlipOutput::out: return o.out;
    case FlipOutput::exposure_map: return o.exposure_map;
    case FlipOutput::csv: return o.csv;
    case FlipOutput::histogram: return o.histogram;
    }
    return o.out;
}

std::string lowercase_extension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return std::tolower(c); });
    return extension;
}

namespace {

// `output`'s own conflicts: its format, or the same file as an output before it.
std::optional<FlipConflict> check_output(const FlipRunOptions& o, FlipOutput output) {
    using Kind = FlipConflict::Kind;
    const std::string& path = output_path(o, output);
    const std::string extension = lowercase_extension(path);
    const bool map = output == FlipOutput::out || output == FlipOutput::exposure_map;
    if (map && extension != ".exr" && extension != ".png") return FlipConflict{Kind::map_format, output};
    if (output == FlipOutput::histogram && extension != ".png") return FlipConflict{Kind::histogram_format, output};
    for (FlipOutput earlier : kFlipOutputs) {
        if (earlier == output) break;
        if (!output_path(o, earlier).empty() && output_path(o, earlier) == path)
            return FlipConflict{Kind::same_output, output, earlier};
    }
    return std::nullopt;
}

} // namespace

std::optional<FlipConflict> check(const FlipRunOptions& o) {
    using Kind = FlipConflict::Kind;
    if (!check_pixels_per_degree(o.ppd)) return FlipConflict{Kind::pixels_per_degree};
    if (o.tests.empty()) return FlipConflict{Kind::no_tests};
    if (o.tests.size() > 1 && (!o.out.empty() || !o.exposure_map.empty()))
        return FlipConflict{Kind::maps_of_several_tests};
    for (FlipOutput output : kFlipOutputs)
        if (!output_path(o, output).empty())
            if (auto conflict = check_output(o, output)) return conflict;
    return std::nullopt;
}

} // namespace kdop
