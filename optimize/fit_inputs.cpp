#include "optimize/fit_inputs.h"

#include "accuracy/accuracy_inputs.h"
#include "accuracy/sampled_distance.h"
#include "core/input_files.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <memory>

namespace kdop {
namespace {

constexpr std::string_view kFiniteForFitting = "fitting needs finite colors";

Result<Image> load_image(const std::string& path, InputSpace space, const ColorMap& map) {
    auto image = read_finite_image(path, kFiniteForFitting, space);
    if (!image) return image;
    // One color throughout: every neighborhood is a point, every k-DOP has volume 0, and the fit
    // would choose among sets that all score 0.
    if (std::ranges::all_of(image->pixels,
                            [&](const glm::vec4& p) { return glm::vec3(p) == glm::vec3(image->pixels[0]); }))
        return fail(fmt::format("{}: every pixel is ({}, {}, {}), so every neighborhood is flat and there is "
                                "nothing to fit to; give images with the scene's detail",
                                path, image->pixels[0].r, image->pixels[0].g, image->pixels[0].b));
    if (auto ok = map_colors(map, image->pixels, image->width, path); !ok) return std::unexpected(ok.error());
    return image;
}

// A 3x3 neighborhood needs 3x3 pixels: in an image, or in each frame of a sequence.
Result<void> check_neighborhood_fits(const std::string& name, std::uint32_t width, std::uint32_t height,
                                     bool sequence) {
    if (width >= 3 && height >= 3) return {};
    return fail(fmt::format("{}: {}x{} {} no 3x3 neighborhood; {} needs at least 3x3 pixels", name, width, height,
                            sequence ? "frames have" : "has", sequence ? "a frame" : "an image"));
}

// The frames of `sequence` a fit reads: every frame_step-th from the first, those held out left out.
std::vector<std::size_t> stepped_frames(const Sequence& sequence, std::size_t step, const Holdout& holdout) {
    std::vector<std::size_t> frames;
    for (std::size_t i = 0; i < sequence.frames.size(); i += step)
        if (!holdout.held_out(i)) frames.push_back(i);
    return frames;
}

} // namespace

Result<FitInputs> fit_inputs(const FitInputOptions& o) {
    // An input given twice would only weigh twice, and the distance's image pairs refuse it.
    if (auto ok = check_distinct_files(o.images, "--images"); !ok) return std::unexpected(ok.error());
    if (auto ok = check_distinct_files(o.sequences, "--sequence"); !ok) return std::unexpected(ok.error());
    FitInputs in;
    std::vector<std::string> described;
    for (const std::string& path : o.images) {
        auto size = read_image_size(path);
        if (!size) return std::unexpected(size.error());
        if (auto ok = check_neighborhood_fits(path, size->x, size->y, false); !ok) return std::unexpected(ok.error());
        in.frames.push_back({path, std::uint64_t(size->x) * size->y, [path, space = o.input_space, map = o.color_map] {
                                 return load_image(path, space, map);
                             }});
        in.paths.emplace_back(path);
        described.push_back(path);
    }
    for (const std::string& dir : o.sequences) {
        auto read = read_sequence(dir);
        if (!read) return std::unexpected(read.error());
        if (auto ok = check_neighborhood_fits(dir, read->width, read->height, true); !ok)
            return std::unexpected(ok.error());
        // Shared by the frames' loaders, which outlive this function.
        const auto shared = std::make_shared<const Sequence>(std::move(*read));
        in.sequences.push_back(shared);
        const Sequence& sequence = *shared;
        const std::vector<std::size_t> frames = stepped_frames(sequence, o.frame_step, o.holdout);
        for (std::size_t index : frames) {
            const std::string label = sequence.frames[index].color.string();
            in.frames.push_back(
                {label, std::uint64_t(sequence.width) * sequence.height,
                 [shared, index, space = o.input_space, map = o.color_map]() -> Result<Image> {
                     auto color = load_frame_color(*shared, index, space);
                     if (!color) return color;
                     if (auto ok = map_colors(map, color->pixels, color->width, shared->frames[index].color.string());
                         !ok)
                         return std::unexpected(ok.error());
                     return color;
                 }});
            in.paths.push_back(sequence.frames[index].color);
        }
        in.paths.push_back(sequence.dir / "sequence.json");
        described.push_back(frames.size() == sequence.frames.size()
                                ? fmt::format("{} ({} frames)", sequence.dir.string(), frames.size())
                            : o.holdout.block
                                ? fmt::format("{} ({} of {} frames, every other block of {} after {} held out)",
                                              sequence.dir.string(), frames.size(), sequence.frames.size(),
                                              o.holdout.block, o.holdout.warmup)
                                : fmt::format("{} ({} of {} frames, every {})", sequence.dir.string(), frames.size(),
                                              sequence.frames.size(), o.frame_step));
    }
    in.description = fmt::format("{}", fmt::join(described, ", "));
    return in;
}

Result<std::vector<ClipSample>> fit_distance_samples(const FitInputOptions& o, const FitInputs& inputs,
                                                     Neighborhood shape, std::size_t per_input, std::uint64_t seed) {
    std::size_t frames = o.images.size();
    for (const auto& sequence : inputs.sequences) frames += stepped_frames(*sequence, o.frame_step, o.holdout).size();
    Progress progress(fmt::format("the ideal clip on up to {} sampled pixels of", per_input), frames);
    std::vector<ClipSample> samples;
    if (!o.images.empty()) {
        auto pairs = image_pairs(o.images, o.input_space);
        if (!pairs) return std::unexpected(pairs.error());
        for (AccuracyPair& pair : *pairs)
            for (Image* image : {&pair.current, &pair.history})
                if (auto ok = map_colors(o.color_map, image->pixels, image->width, pair.name); !ok)
                    return std::unexpected(ok.error());
        auto drawn = ideal_clip_samples(*pairs, shape, per_input, seed);
        if (!drawn) return std::unexpected(drawn.error());
        samples = std::move(*drawn);
        for (const std::string& image : o.images) progress.advance(image);
    }
    // A sequence's pixels are spread over its frames, each frame drawing with its own generator.
    for (const auto& shared : inputs.sequences) {
        const Sequence& sequence = *shared;
        const std::vector<std::size_t> stepped = stepped_frames(sequence, o.frame_step, o.holdout);
        const std::size_t per_frame = (per_input + stepped.size() - 1) / stepped.size();
        for (std::size_t index : stepped) {
            auto color = load_frame_color(sequence, index, o.input_space);
            if (!color) return std::unexpected(color.error());
            if (auto ok = map_colors(o.color_map, color->pixels, color->width, sequence.frames[index].color.string());
                !ok)
                return std::unexpected(ok.error());
            const std::string family = fmt::format("{} frame {}", sequence.name, index);
            auto drawn = ideal_clip_samples(ghosting_pairs(family, *color), shape, per_frame,
                                            seed + (index + 1) * 0x9e3779b97f4a7c15ull);
            if (!drawn) return std::unexpected(drawn.error());
            std::ranges::move(*drawn, std::back_inserter(samples));
            progress.advance(family);
        }
    }
    progress.finish();
    return samples;
}

} // namespace kdop
