#include "temporal/viewer_frames.h"

#include "core/parallel_for.h"
#include "flip/magma.h"
#include "temporal/picture_flip.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace kdop {
namespace {

// A staged image: its width, height and float RGBA pixels as they are in memory. The process
// reads back only what it wrote itself, moments before, so no format is needed, and many frames
// are staged and dropped during a pass: an EXR's compression and OpenImageIO's checks cost more
// there than the whole copy (written by hand for that reason).
Result<void> write_staged(const std::filesystem::path& path, const Image& image) {
    std::ofstream out(path, std::ios::binary);
    const std::uint32_t size[2] = {image.width, image.height};
    out.write(reinterpret_cast<const char*>(size), sizeof size);
    out.write(reinterpret_cast<const char*>(image.pixels.data()),
              std::streamsize(image.pixels.size() * sizeof(glm::vec4)));
    if (!out.flush()) return fail(fmt::format("{}: cannot write the viewer's staged frame", path.string()));
    return {};
}

Result<Image> read_staged(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::uint32_t size[2] = {0, 0};
    in.read(reinterpret_cast<char*>(size), sizeof size);
    Image image(size[0], size[1]);
    in.read(reinterpret_cast<char*>(image.pixels.data()), std::streamsize(image.pixels.size() * sizeof(glm::vec4)));
    if (!in) return fail(fmt::format("{}: cannot read the viewer's staged frame back", path.string()));
    return image;
}

} // namespace

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
    ViewerSequence shown;                              // its frames, worst and figures filled at write()
    std::vector<std::size_t> spread;                   // ascending
    std::vector<double> worst_value;                   // per variant; NaN never beats it
    std::map<std::size_t, std::vector<double>> staged; // frame: each variant's figure on it
    std::map<std::size_t, bool> has_previous;          // frame: whether the outputs before it were staged
};

ViewerFrames::ViewerFrames(std::size_t spread, std::vector<std::string> variants)
    : spread_(spread), variants_(std::move(variants)) {}

std::size_t ViewerFrames::kept_frames() const {
    std::size_t kept = 0;
    for (const auto& sequence : sequences_) kept += sequence->staged.size();
    return kept;
}

void ViewerFrames::plan(const std::string& sequence, const std::string& scene, std::size_t first, std::size_t last,
                        SequenceRoles roles, ColorRange range, bool against_reference) {
    auto kept = std::make_shared<Kept>();
    ViewerSequence& shown = kept->shown;
    shown.name = sequence;
    shown.scene = scene;
    shown.figure = roles.ghosting ? ViewerFigure::ghosting : ViewerFigure::shimmer;
    shown.range = range;
    shown.truth = against_reference ? "reference" : "aliased";
    const char* flip = range == ColorRange::hdr ? "HDR-FLIP" : "LDR-FLIP";
    shown.map = shown.figure == ViewerFigure::shimmer ? fmt::format("{} against the output before", flip)
                : against_reference                   ? fmt::format("{} against the reference", flip)
                                                      : fmt::format("{} against the aliased frame", flip);
    shown.worst.assign(variants_.size(), ViewerSequence::kNone);
    kept->spread = spread_frames(first, last, spread_);
    kept->worst_value.assign(variants_.size(), -INFINITY);
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
    bool keep = std::binary_search(kept.spread.begin(), kept.spread.end(), frame.index);
    for (std::size_t v = 0; v < frame.figures.size(); ++v) {
        const FrameFigures& f = frame.figures[v];
        figures.push_back(kept.shown.figure == ViewerFigure::ghosting ? f.ghosting : f.shimmer);
        if (figures.back() > kept.worst_value[v]) { // NaN never wins; the earliest of equals stays
            kept.worst_value[v] = figures.back();
            kept.shown.worst[v] = frame.index;
            keep = true;
        }
    }
    if (!keep) return {};
    if (auto ok = stage(it->second, frame); !ok) return ok;
    kept.staged[frame.index] = std::move(figures);
    drop_unkept(it->second);
    return {};
}

Result<void> ViewerFrames::stage(std::size_t s, const MeasuredFrame& frame) {
    if (!scratch_) scratch_ = std::make_unique<ScratchDirectory>("kdop-viewer");
    if (scratch_->path.empty())
        return fail("cannot create a scratch folder for the viewer's frames (is TMPDIR writable?)");
    std::error_code ec;
    std::filesystem::create_directories(staged(s, frame.index, "truth").parent_path(), ec);
    if (ec) return fail(fmt::format("{}: {}", scratch_->path.string(), ec.message()));
    if (auto ok = write_staged(staged(s, frame.index, "truth"), *frame.truth); !ok) return ok;
    // The outputs before are what a shimmer map compares against.
    const bool previous = sequences_[s]->shown.figure == ViewerFigure::shimmer && !frame.previous.empty();
    for (std::size_t v = 0; v < frame.outputs.size(); ++v) {
        if (auto ok = write_staged(staged(s, frame.index, std::to_string(v)), *frame.outputs[v]); !ok) return ok;
        if (previous)
            if (auto ok = write_staged(staged(s, frame.index, fmt::format("before-{}", v)), *frame.previous[v]); !ok)
                return ok;
    }
    sequences_[s]->has_previous[frame.index] = previous;
    sequences_[s]->shown.width = frame.truth->width, sequences_[s]->shown.height = frame.truth->height;
    return {};
}

void ViewerFrames::drop_unkept(std::size_t s) {
    Kept& kept = *sequences_[s];
    for (auto it = kept.staged.begin(); it != kept.staged.end();) {
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
        kept.has_previous.erase(index);
        it = kept.staged.erase(it);
    }
}

Result<std::vector<ViewerSequence>> ViewerFrames::write(const HdrFlip& flip, const ExposureOptions& exposure,
                                                        StagedImages& images,
                                                        const std::function<void(const std::string&)>& on_frame) const {
    std::vector<ViewerSequence> shown;
    for (std::size_t s = 0; s < sequences_.size(); ++s) {
        const Kept& kept = *sequences_[s];
        ViewerSequence sequence = kept.shown;
        const PictureFlip shown_as{&flip, sequence.range, exposure};
        auto add = [&](std::size_t index, const std::string& image, bool flip_map, const Image& shown) {
            return images.add(viewer_image_path(sequence, index, image, flip_map), shown);
        };
        // An LDR frame is shown as it is (no copy); an HDR one tone mapped.
        auto add_shown = [&](std::size_t index, const std::string& image, const Image& frame) {
            return sequence.range == ColorRange::hdr ? add(index, image, false, shown_as.shown(frame))
                                                     : add(index, image, false, frame);
        };
        for (const auto& [index, figures] : kept.staged) {
            sequence.frames.push_back(index);
            sequence.figures.push_back(figures);
            auto truth = read_staged(staged(s, index, "truth"));
            if (!truth) return std::unexpected(truth.error());
            // The truth and each variant's output and map, one per core at a time (the truth is item
            // 0); the first error, in that order, is reported.
            std::vector<Result<void>> done(variants_.size() + 1);
            parallel_for(variants_.size() + 1, 0, [&](std::size_t item) {
                if (item == 0) {
                    done[0] = add_shown(index, sequence.truth, *truth);
                    return;
                }
                const std::size_t v = item - 1;
                done[item] = [&]() -> Result<void> {
                    auto output = read_staged(staged(s, index, std::to_string(v)));
                    if (!output) return std::unexpected(output.error());
                    if (auto ok = add_shown(index, variants_[v], *output); !ok) return ok;
                    // Ghosting's map is against the truth, shimmer's against the output before (none
                    // after a camera cut).
                    Result<Image> before = fail("no output before");
                    if (sequence.figure == ViewerFigure::shimmer && kept.has_previous.at(index))
                        if (before = read_staged(staged(s, index, fmt::format("before-{}", v))); !before)
                            return std::unexpected(before.error());
                    const Image* against = sequence.figure == ViewerFigure::ghosting ? &*truth
                                           : before                                  ? &*before
                                                                                     : nullptr;
                    if (!against) return {};
                    auto map = shown_as.map(*against, *output);
                    if (!map) return fail(fmt::format("{} frame {}: {}", sequence.name, index, map.error().message));
                    return add(index, variants_[v], true, flip::magma_image(*map, output->width, output->height));
                }();
            });
            for (const Result<void>& ok : done)
                if (!ok) return std::unexpected(ok.error());
            if (on_frame) on_frame(sequence.name);
        }
        shown.push_back(std::move(sequence));
    }
    return shown;
}

} // namespace kdop
