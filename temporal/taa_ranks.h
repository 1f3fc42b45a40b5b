// `kdop taa` over MPI ranks (harness/ranks.h). Its work is split by source, not by variant: one
// source's frames are read or drawn once and resolved by every variant in one pass (taa_measure.h),
// and what is shown of a source needs every variant's output on the same frames (the frame where
// they differ most, each variant's worst frame in the viewer), which only one rank holding them all
// can choose. Sources go to ranks balanced by frames x output pixels x shaders; each rank measures
// its own and stages their images; rank 0 gathers the figures (CBOR) and the images (one file at a
// time) and writes every output, so the files do not depend on the rank count.
#pragma once

#include "core/result.h"
#include "harness/ranks.h"
#include "harness/run_metadata.h"
#include "harness/staged_images.h"
#include "temporal/taa_evaluation.h"
#include "temporal/taa_sources.h"
#include "temporal/viewer_frames.h"

#include <optional>
#include <string>
#include <vector>

namespace kdop {

// What one source's measurement gives the report.
struct MeasuredSource {
    std::vector<EvaluationRow> rows;    // each shader's, in order (EvaluationRow::trail dropped)
    std::string picture;                // its ghosting picture's name; empty where it has none
    std::vector<ViewerSequence> viewed; // what the viewer shows of it: a scene's two sequences, else one
};

// The rank that measures each of `sources`' sources, in TaaSources order (scenes, sequences,
// captures): Ranks::balance of each one's frames x output pixels x shaders.
std::vector<int> source_owners(const Ranks& ranks, const TaaSources& sources, const TaaEvaluation& evaluation,
                               const TaaSchedule& schedule);

// The viewer's sequences of source `i` (in TaaSources order): a scene has two.
std::size_t viewed_sequences(const TaaSources& sources, std::size_t i);

// What every rank measured, on rank 0: `mine` holds this rank's sources (by source index, nullopt
// for another's), and `images` its staged images, which go to rank 0's `images`. Returns every
// source's measurement on rank 0 (each source measured by exactly one rank), and each rank's
// `me` (its device and seconds; RunMetadata::RankShare::measured is left to the caller); on the
// other ranks, nothing. A rank that cannot send or stage a file stops every
// rank (Ranks::abort): the others are inside the exchange.
struct GatheredSources {
    std::vector<MeasuredSource> sources;
    std::vector<RunMetadata::RankShare> shares; // by rank
};
GatheredSources gather_sources(const Ranks& ranks, std::vector<std::optional<MeasuredSource>> mine,
                               const RunMetadata::RankShare& me, StagedImages& images);

// A measured source in CBOR (through nlohmann::json: doubles exactly, NaN kept) and back: what
// gather_sources sends; exposed for its test.
std::string measured_source_bytes(const MeasuredSource& source);
Result<MeasuredSource> measured_source_from(const std::string& bytes);

} // namespace kdop
