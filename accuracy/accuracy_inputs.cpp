#include "accuracy/accuracy_inputs.h"

#include "core/input_files.h"

#include "images/image_io.h"
#include "images/texture_cases.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include <cmath>
#include <filesystem>

namespace kdop {
namespace {

// The ideal clip is defined for finite colors only (an unusable history is a stress-suite matter).
constexpr std::string_view kFiniteForAccuracy = "accuracy needs finite colors (see `kdop stress` for NaN and Inf)";

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

Image rotated_half_turn(const Image& image) {
    Image out(image.width, image.height);
    for (std::uint32_t y = 0; y < image.height; ++y)
        for (std::uint32_t x = 0; x < image.width; ++x)
            out.at(x, y) = image.at(image.width - 1 - x, image.height - 1 - y);
    return out;
}

} // namespace

std::vector<AccuracyPair> builtin_pairs(std::uint32_t width, std::uint32_t height, std::uint64_t seed) {
    std::vector<AccuracyPair> pairs;
    for (TestCase& c : make_test_cases(width, height, seed))
        if (c.model != HistoryModel::same)
            pairs.push_back({c.texture, c.name(), std::move(c.current), std::move(c.history)});
    return pairs;
}

Result<std::vector<AccuracyPair>> image_pairs(const std::vector<std::string>& paths, InputSpace space) {
    if (auto ok = check_distinct_files(paths, "--images"); !ok) return std::unexpected(ok.error());
    std::vector<AccuracyPair> pairs;
    for (const std::string& path : paths) {
        // An image is its family, named by its file's stem, or by the path as given where two files
        // share a stem (frame.exr from two folders): rows and charts must not merge them.
        const bool shared_stem =
            std::ranges::count_if(paths, [&](const std::string& p) { return stem(p) == stem(path); }) > 1;
        const std::string family = shared_stem ? path : stem(path);
        auto current = read_finite_image(path, kFiniteForAccuracy, space);
        if (!current) return std::unexpected(current.error());
        std::ranges::move(ghosting_pairs(family, *current), std::back_inserter(pairs));
    }
    return pairs;
}

std::vector<AccuracyPair> ghosting_pairs(const std::string& family, const Image& current) {
    std::vector<AccuracyPair> pairs;
    const Image other = rotated_half_turn(current);
    for (HistoryModel m : history_models())
        if (m != HistoryModel::same)
            pairs.push_back(
                {family, fmt::format("{}/{}", family, to_string(m)), current, make_history(current, m, other)});
    return pairs;
}

Result<AccuracyPair> given_pair(const std::string& current_path, const std::string& history_path, InputSpace space) {
    auto current = read_finite_image(current_path, kFiniteForAccuracy, space);
    if (!current) return std::unexpected(current.error());
    auto history = read_finite_image(history_path, kFiniteForAccuracy, space);
    if (!history) return std::unexpected(history.error());
    if (current->width != history->width || current->height != history->height)
        return fail(fmt::format("--history: {} is {}x{} but --current {} is {}x{}", history_path, history->width,
                                history->height, current_path, current->width, current->height));
    return AccuracyPair{stem(current_path), stem(current_path), std::move(*current), std::move(*history)};
}

} // namespace kdop
