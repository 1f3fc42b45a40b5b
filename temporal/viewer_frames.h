// The frames report.html's viewer shows (taa_report_page.h): of each sequence measured, a bounded
// set of measured frames, chosen as the pass goes, with every variant's output on them, the truth
// and each output's FLIP map, written as PNGs under viewer/<sequence>/<frame>/.
//
// The frames kept of a sequence are `spread` measured frames spread evenly from the first to the
// last, and each variant's worst frame: where its figure (ghosting where the sequence measures it,
// else shimmer: maps_show_ghosting) is largest, the earliest of equals. The spread frames are known
// before the pass, so their PNGs are written as they are measured. Worst frames are known only at
// the end, so each frame that is one so far is staged (its float pixels and the maps measured on
// it, in a scratch folder) and deleted when it no longer is. The pass holds none of the outputs in
// memory, and no map is computed twice.
#pragma once

#include "core/result.h"
#include "flip/hdr_flip.h"
#include "harness/scratch_directory.h"
#include "harness/staged_images.h"
#include "sequence/sequence.h"
#include "temporal/taa_measure.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace kdop {

// What the viewer shows of one sequence once the pass is over.
struct ViewerSequence {
    std::string name;               // the sequence's (a scene's: <scene>-shimmer, <scene>-ghosting)
    std::string scene;              // taa.csv's row it belongs to
    std::size_t figure = kGhosting; // the metric its maps show (MetricId): ghosting, else shimmer
    ColorRange range = ColorRange::ldr;
    std::string truth; // the truth image's name: "reference" or "aliased"
    std::string map;   // what the FLIP maps compare: "LDR-FLIP against the aliased frame"
    std::uint32_t width = 0, height = 0;
    std::vector<std::size_t> frames; // the frames kept, ascending
    static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
    std::vector<std::size_t> worst;           // per variant: its worst frame; kNone where it has no figure
    std::vector<std::vector<double>> figures; // per kept frame, per variant: the figure on it (NaN: none)
    // How many of the run's variants, the first ones, the sequence was resolved by: the spatial-only
    // upscale, last, only where it upscales.
    std::size_t variants = 0;
};

// The `spread` measured frames of `first`..`last` spread evenly, both ends among them (one: the
// first); all of them where there are no more than `spread`.
std::vector<std::size_t> spread_frames(std::size_t first, std::size_t last, std::size_t spread);

// The path of one of a kept frame's images, relative to the output folder: viewer/<sequence>/
// viewer/<scene>/<sequence>/<frame, 4 digits>/<image>.png (`scene` the taa.csv row: a user's
// sequence is its own), the image a variant's name or the truth's, or flip/<variant>.png.
std::string viewer_image_path(const ViewerSequence& sequence, std::size_t frame, const std::string& image,
                              bool flip_map = false);

// Keeps the frames of every sequence measured in one run; its observer() goes into the
// evaluation's (EvaluationObserver::measured).
class ViewerFrames {
public:
    // `spread` frames per sequence besides the worst ones; `variants` is the variants' names. The
    // PNGs go into `images` (which must outlive this), HDR frames tone mapped with
    // exposure.tone_mapper at exposure 0.
    ViewerFrames(std::size_t spread, std::vector<std::string> variants, StagedImages& images,
                 const ExposureOptions& exposure);

    // Before a sequence's pass: its name, the taa.csv row it belongs to, its measured frames
    // (`first`..`last`), what it measures and against what, and how many of the variants (the
    // first ones; 0: all) resolve it.
    void plan(const std::string& sequence, const std::string& scene, std::size_t first, std::size_t last,
              SequenceRoles roles, ColorRange range, bool against_reference, std::size_t variants = 0);

    // Before measuring a scene or sequence, its name: a user's sequence may share its name with
    // one of a scene's (grass-ghosting), so frames are offered as of the source measured.
    void measuring(const std::string& scene) { measuring_ = scene; }

    // Takes each measured frame that is kept so far (of a sequence planned for the source being
    // measured), with its maps (the frame must carry them: EvaluationObserver::maps): a spread
    // frame's PNGs are written now, a worst frame so far is staged; drops those that no longer are.
    // A kept frame's PNGs (in `images`, moved into the output folder with the rest) are every
    // variant's output and the FLIP map its figure was measured with (LDR-FLIP, or HDR-FLIP for
    // an HDR sequence; against the truth for ghosting, the output before for shimmer, none after a
    // camera cut), in magma, and the truth; a frame's images are made on every core.
    Result<void> offer(const MeasuredFrame& frame);

    // After the pass: the PNGs of the staged frames. Returns what the viewer shows of each
    // sequence, in the order planned. `on_frame` is called after each staged frame, naming its
    // sequence.
    Result<std::vector<ViewerSequence>> write(const std::function<void(const std::string&)>& on_frame = {}) const;
    // The frames staged so far, over every sequence: write()'s steps.
    std::size_t staged_frames() const;

private:
    struct Kept; // one sequence's frames so far
    // The staged file of image `name` of frame `index` of sequence `s`.
    std::filesystem::path staged(std::size_t s, std::size_t index, const std::string& name) const;
    Result<void> stage(std::size_t s, const MeasuredFrame& frame, std::span<const Image* const> outputs);
    void drop_unkept(std::size_t s);
    // `truth` and `variant` for each of `variants` variants, one per core at a time; the first
    // error in that order.
    Result<void> on_every_core(std::size_t variants, const std::function<Result<void>()>& truth,
                               const std::function<Result<void>(std::size_t v)>& variant) const;
    // Frame `index`'s PNGs: the truth, and each variant's output and map (none where empty).
    Result<void> write_frame(const ViewerSequence& sequence, std::size_t index, const Image& truth,
                             std::span<const Image* const> outputs, std::span<const std::vector<float>> maps) const;
    Result<void> add_shown(const ViewerSequence& sequence, std::size_t index, const std::string& name,
                           const Image& frame) const;
    Result<void> add_map(const ViewerSequence& sequence, std::size_t index, std::size_t v,
                         std::span<const float> map) const;

    std::size_t spread_;
    std::vector<std::string> variants_;
    StagedImages* images_;
    ExposureOptions exposure_;
    std::vector<std::shared_ptr<Kept>> sequences_;
    std::map<std::pair<std::string, std::string>, std::size_t> by_name_; // by scene and sequence
    std::string measuring_;
    std::unique_ptr<ScratchDirectory> scratch_; // made when the first frame is staged
};

} // namespace kdop
