#include "temporal/viewer_frames.h"

#include "core/parallel_for.h"
#include "flip/magma.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <span>

namespace kdop {

std::vector<std::size_t> spread_frames(std::size_t first, std::size_t last, std::size_t spread) {
    std::vector<std::size_t> frames;
    const std::size_t measured = last - first + 1;
    if (spread == 0) return frames;
    if (spread >= measured) {
        for (std::size_t i = first; i <= last; ++i) frames.push_back(i);
        return frames;
    }
    if (spread == 1) return {first};
    // Rounded to the nearest frame; distinct, since the step is above 1.
    for (std::size_t k = 0; k < spread; ++k)
        frames.push_back(first + (k * (measured - 1) + (spread - 1) / 2) / (spread - 1));
    return frames;
}

std::string viewer_image_path(const ViewerSequence& sequence, std::size_t frame, const std::string& image,
                              bool flip_map) {
    return fmt::format("viewer/{}/{}/{:04}/{}{}.png", sequence.scene, sequence.name, frame, flip_map ? "flip/" : "",
                       image);
}

struct ViewerFrames::Kept {
    ViewerSequence shown;                               // its frames, worst and figures filled at write()
    std::vector<std::size_t> spread;                    // ascending
    std::vector<double> worst_value;                    // per variant; NaN never beats it
    std::map<std::size_t, std::vector<double>> figures; // frame kept: each variant's figure on it
    std::map<std::size_t, std::vector<bool>> has_map;   // frame staged: per variant, whether its map was
};

ViewerFrames::ViewerFrames(std::size_t spread, std::vector<std::string> variants, StagedImages& images,
                           const ExposureOptions& exposure)
    : spread_(spread), variants_(std::move(variants)), images_(&images), exposure_(exposure) {}

std::size_t ViewerFrames::staged_frames() const {
    std::size_t staged = 0;
    for (const auto& sequence : sequences_) staged += sequence->has_map.size();
    return staged;
}

void ViewerFrames::plan(const std::string& sequence, const std::string& scene, std::size_t first, std::size_t last,
                        SequenceRoles roles, ColorRange range, bool against_reference, std::size_t variants) {
    auto kept = std::make_shared<Kept>();
    ViewerSequence& shown = kept->shown;
    shown.name = sequence;
    shown.scene = scene;
    shown.figure = maps_show_ghosting(roles) ? kGhosting : kShimmer;
    shown.range = range;
    shown.truth = against_reference ? "reference" : "aliased";
    const char* flip = range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP";
    shown.map = shown.figure == kShimmer ? fmt::format("{} against the output before", flip)
                : against_reference      ? fmt::format("{} against the reference", flip)
                                         : fmt::format("{} against the aliased frame", flip);
    shown.variants = variants == 0 ? variants_.size() : std::min(variants, variants_.size());
    shown.worst.assign(shown.variants, ViewerSequence::kNone);
    kept->spread = spread_frames(first, last, spread_);
    kept->worst_value.assign(shown.variants, -INFINITY);
    by_name_[{scene, sequence}] = sequences_.size();
    sequences_.push_back(std::move(kept));
}

std::filesystem::path ViewerFrames::staged(std::size_t s, std::size_t index, const std::string& name) const {
    return scratch_->path / std::to_string(s) / std::to_string(index) / (name + ".raw");
}

Result<void> ViewerFrames::offer(const MeasuredFrame& frame) {
    auto it = by_name_.find({measuring_, std::string(frame.sequence)});
    if (it == by_name_.end()) return {};
    Kept& kept = *sequences_[it->second];
    std::vector<double> figures;
    const bool spread = std::binary_search(kept.spread.begin(), kept.spread.end(), frame.index);
    bool keep = spread;
    if (frame.figures.size() != kept.shown.variants)
        return fail(fmt::format("{}: {} outputs offered to the viewer, which planned {}", frame.sequence,
                                frame.figures.size(), kept.shown.variants));
    for (std::size_t v = 0; v < frame.figures.size(); ++v) {
        const FrameFigures& f = frame.figures[v];
        figures.push_back(f.value(kept.shown.figure));
        if (figures.back() > kept.worst_value[v]) { // NaN never wins; the earliest of equals stays
            kept.worst_value[v] = figures.back();
            kept.shown.worst[v] = frame.index;
            keep = true;
        }
    }
    if (!keep) return {}; // its outputs never come to the host
    if (frame.maps.size() != frame.figures.size())
        return fail("the viewer shows each output's FLIP map, and the frame came without them (measure with "
                    "EvaluationObserver::maps)");
    auto outputs = frame.outputs();
    if (!outputs) return std::unexpected(outputs.error());
    kept.shown.width = frame.truth->width, kept.shown.height = frame.truth->height;
    // A spread frame is kept whatever comes later: its PNGs are written now, on every core. A worst
    // frame so far may stop being one, so it is staged until the end.
    if (auto ok = spread ? write_frame(kept.shown, frame.index, *frame.truth, *outputs, frame.maps)
                         : stage(it->second, frame, *outputs);
        !ok)
        return ok;
    kept.figures[frame.index] = std::move(figures);
    drop_unkept(it->second);
    return {};
}

Result<void> ViewerFrames::stage(std::size_t s, const MeasuredFrame& frame, std::span<const Image* const> outputs) {
    if (!scratch_) scratch_ = std::make_unique<ScratchDirectory>("kdop-viewer");
    if (scratch_->path.empty())
        return fail("cannot create a scratch folder for the viewer's frames (is TMPDIR writable?)");
    std::error_code ec;
    std::filesystem::create_directories(staged(s, frame.index, "truth").parent_path(), ec);
    if (ec) return fail(fmt::format("{}: {}", scratch_->path.string(), ec.message()));
    if (auto ok = write_raw(staged(s, frame.index, "truth"), *frame.truth); !ok) return ok;
    std::vector<bool> has_map;
    for (std::size_t v = 0; v < outputs.size(); ++v) {
        if (auto ok = write_raw(staged(s, frame.index, std::to_string(v)), *outputs[v]); !ok) return ok;
        // The map the figure was measured with; none for shimmer after a camera cut.
        has_map.push_back(!frame.maps[v].empty());
        if (has_map.back())
            if (auto ok = write_raw(staged(s, frame.index, fmt::format("flip-{}", v)), frame.maps[v]); !ok) return ok;
    }
    sequences_[s]->has_map[frame.index] = std::move(has_map);
    return {};
}

void ViewerFrames::drop_unkept(std::size_t s) {
    Kept& kept = *sequences_[s];
    for (auto it = kept.figures.begin(); it != kept.figures.end();) {
        const std::size_t index = it->first;
        const bool wanted =
            std::binary_search(kept.spread.begin(), kept.spread.end(), index) ||
            std::find(kept.shown.worst.begin(), kept.shown.worst.end(), index) != kept.shown.worst.end();
        if (wanted) {
            ++it;
            continue;
        }
        std::error_code ignored;
        std::filesystem::remove_all(staged(s, index, "truth").parent_path(), ignored);
        kept.has_map.erase(index);
        it = kept.figures.erase(it);
    }
}

Result<void> ViewerFrames::add_shown(const ViewerSequence& sequence, std::size_t index, const std::string& name,
                                     const Image& frame) const {
    const std::string path = viewer_image_path(sequence, index, name);
    // An LDR frame is shown as it is (no copy); an HDR one tone mapped, as PictureFlip::shown does.
    return sequence.range == ColorRange::hdr
               ? images_->add(path, HdrFlip::tone_mapped(frame, exposure_.tone_mapper, 0.0f))
               : images_->add(path, frame);
}

Result<void> ViewerFrames::add_map(const ViewerSequence& sequence, std::size_t index, std::size_t v,
                                   std::span<const float> map) const {
    if (map.empty()) return {}; // shimmer after a camera cut
    return images_->add(viewer_image_path(sequence, index, variants_[v], true),
                        flip::magma_image(map, sequence.width, sequence.height));
}

Result<void> ViewerFrames::on_every_core(std::size_t variants, const std::function<Result<void>()>& truth,
                                         const std::function<Result<void>(std::size_t v)>& variant) const {
    // The truth is item 0; the first error, in item order, is reported.
    std::vector<Result<void>> done(variants + 1);
    parallel_for(variants + 1, 0, [&](std::size_t item) { done[item] = item == 0 ? truth() : variant(item - 1); });
    for (const Result<void>& ok : done)
        if (!ok) return ok;
    return {};
}

Result<void> ViewerFrames::write_frame(const ViewerSequence& sequence, std::size_t index, const Image& truth,
                                       std::span<const Image* const> outputs,
                                       std::span<const std::vector<float>> maps) const {
    return on_every_core(
        sequence.variants, [&] { return add_shown(sequence, index, sequence.truth, truth); },
        [&](std::size_t v) -> Result<void> {
            if (auto ok = add_shown(sequence, index, variants_[v], *outputs[v]); !ok) return ok;
            return add_map(sequence, index, v, maps[v]);
        });
}

Result<std::vector<ViewerSequence>> ViewerFrames::write(const std::function<void(const std::string&)>& on_frame) const {
    std::vector<ViewerSequence> shown;
    for (std::size_t s = 0; s < sequences_.size(); ++s) {
        const Kept& kept = *sequences_[s];
        ViewerSequence sequence = kept.shown;
        for (const auto& [index, figures] : kept.figures) {
            sequence.frames.push_back(index);
            sequence.figures.push_back(figures);
            const auto staged_maps = kept.has_map.find(index);
            if (staged_maps == kept.has_map.end()) continue; // a spread frame, written as it was measured
            // As write_frame, each image read back on the core that writes it.
            auto written = on_every_core(
                sequence.variants,
                [&]() -> Result<void> {
                    auto truth = read_raw_image(staged(s, index, "truth"), sequence.width, sequence.height);
                    if (!truth) return std::unexpected(truth.error());
                    return add_shown(sequence, index, sequence.truth, *truth);
                },
                [&](std::size_t v) -> Result<void> {
                    auto output = read_raw_image(staged(s, index, std::to_string(v)), sequence.width, sequence.height);
                    if (!output) return std::unexpected(output.error());
                    if (auto ok = add_shown(sequence, index, variants_[v], *output); !ok) return ok;
                    std::vector<float> map;
                    if (staged_maps->second[v]) {
                        map.resize(std::size_t(sequence.width) * sequence.height);
                        if (auto ok = read_raw(staged(s, index, fmt::format("flip-{}", v)), map); !ok) return ok;
                    }
                    return add_map(sequence, index, v, map);
                });
            if (!written) return std::unexpected(written.error());
            if (on_frame) on_frame(sequence.name);
        }
        shown.push_back(std::move(sequence));
    }
    return shown;
}

} // namespace kdop
