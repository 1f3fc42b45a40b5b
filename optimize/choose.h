// `kdop choose`: from a game's frames to the variant it ships. Axis sets are fitted to some
// sequences (the optimize fit, one set per axis count), then every candidate, the fitted sets and
// the built-in ones in each mode and neighborhood asked for, is measured on other sequences, or on
// blocks of frames left out of the fit (Holdout), with kdop taa's evaluation (temporal/taa_evaluation.h, the same
// call): no figure a choice rests on comes from the frames a set was fitted to. The recommendation is the candidate
// with the least held-out ghosting within a cost budget, or the cheapest that meets a ghosting
// target; a built-in set wins whenever it is better. Every held-out ghosting comes with a block
// bootstrap interval (harness/block_bootstrap.h), and the recommendation says when the runner-up
// is within it. Every figure is in one FLIP mode: fit and held-out sequences of two color ranges
// (LDR-FLIP beside HDR-FLIP, whose scales differ) are refused.
#pragma once

#include "core/result.h"
#include "core/variant_key.h"
#include "harness/block_bootstrap.h"
#include "harness/ranks.h"
#include "optimize/fit_inputs.h"
#include "runtime/context.h"
#include "temporal/taa_evaluation.h"

#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

struct ChooseOptions {
    std::vector<std::string> fit, validate; // sequence folders: fitted to, and held out
    // Without `validate`: frames of the fit sequences held out instead, every other block of this
    // many after the warm-up (Holdout); 0: none.
    std::size_t holdout = 0;
    std::vector<std::size_t> fit_axes{4, 8, 16}; // one fitted set per count
    std::vector<std::string> sets;               // built-in candidates; empty: every built-in set
    // Empty: the default selection kdop gen and kdop taa make too (kCommandDefaults, variant_spec.h).
    std::vector<std::string> modes, neighborhoods;
    std::optional<std::size_t> budget_ops; // the most float ops a candidate's clip may cost
    std::optional<double> budget_ms;       // or the longest median device time its pass may take
    std::optional<double> target_ghosting; // else: the cheapest whose held-out ghosting reaches it
    EvaluationOptions evaluation;          // kdop taa's, as --warmup, --ppd and the resolve options set it
    unsigned timing_rounds = 15;           // interleaved dispatches per candidate, as kdop taa's
    bool lavapipe_cost = false; // also count each clip candidate's lavapipe instructions per pixel (callgrind)
    InputSpace input_space = InputSpace::from_file;
    // The fit's: its color space is the resolve's (evaluation.resolve.color_map).
    std::uint64_t seed = 1; // of the fit, and of the bootstrap of the held-out ghosting
    unsigned threads = 0;
    std::optional<std::size_t> sample; // fit on this many sampled neighborhoods
    std::string out;                   // the folder the fitted sets are named for (fitted<N>.axes)
    bool chart = true;                 // choice.png (none where gnuplot is missing)
};

// Options of kdop choose that do not go together, in its own terms; the command line words them
// with its flags (cli/choose_command.cpp).
struct ChooseConflict {
    enum class Kind {
        nothing_held_out,    // neither validate nor holdout: no frame the sets were not fitted to
        held_out_twice,      // both validate and holdout
        nothing_fitted,      // no fit sequence
        fitted_and_held_out, // a validate sequence is also a fit one (`sequence`, as validate gives it)
        two_rules,           // more than one of budget_ops, budget_ms and target_ghosting
    };
    Kind kind;
    std::string sequence;
};

// The first conflict of the options, or none. Writes and reads nothing; only the sequences'
// folders are looked up, for one given to both fit and validate however it is spelled.
std::optional<ChooseConflict> check(const ChooseOptions& options);

// One metric's figures of a candidate: its mean over the sequences on the fit frames and on the
// held-out frames (each sequence's mean over its measured frames, as kdop taa's taa.csv), and the
// median and 95th percentile over every held-out frame together. NaN where not measured.
struct CandidateFigure {
    double fit = NAN, held_out = NAN, held_out_median = NAN, held_out_p95 = NAN;
};

// One candidate: a variant, what its clip costs and what it leaves on the fit and held-out frames.
struct Candidate {
    VariantKey key;
    bool fitted = false;
    int rank = 0; // the rank that measured its figures (under mpirun; its timing is rank 0's)
    // The float ops of its compute shader's SPIR-V as the generator counts them (spirv_cost.h): the
    // count kdop gen and kdop bench print, which --budget-ops is held against. Beside it the
    // analytic lower bound of the same clip (analytic_cost.h; bench's "analytic min"), a few below.
    std::size_t float_ops = 0, analytic_ops = 0;
    // The device time of its rectification pass at the sequences' frame size, as kdop taa times it:
    // the median and quartiles over interleaved rounds.
    double ms = NAN, ms_q1 = NAN, ms_q3 = NAN;
    // With lavapipe_cost, the instructions per pixel lavapipe runs for its clip beyond the gather,
    // counted by callgrind as kdop bench counts them; NaN where not counted (varclip has no count).
    double lavapipe_instructions = NAN;
    // Each metric's figures, by metric (the evaluation's registry, temporal/metrics.h).
    std::vector<CandidateFigure> figures;
    // The held-out figure the rules rank by, kdop's ranking metric's (ghosting), and the same on the
    // fit frames.
    double ranked() const { return kGhosting < figures.size() ? figures[kGhosting].held_out : NAN; }
    double ranked_fit() const { return kGhosting < figures.size() ? figures[kGhosting].fit : NAN; }
    // What every FLIP figure is in: LDR-FLIP, or HDR-FLIP for HDR sequences (one per run).
    ColorRange range = ColorRange::ldr;
    // ranked()'s bootstrap replicates (paired with every other candidate's: the same frames drawn),
    // their interval, and whether ranked() is within noise of the recommended one's (of the least,
    // where none is): the paired difference's interval holds 0. Empty, unknown and nullopt where
    // the held-out frames are too few for an interval.
    std::vector<double> replicates;
    Interval interval;
    std::optional<bool> within_noise;
    bool ms_noise = false; // its median ms within the larger interquartile range of its own and the fastest's
};

// The coverage of every interval choose reports.
inline constexpr double kChoiceLevel = 0.95;

// Which candidate to ship, and why, in words. The runner-up is the one the rule would choose were
// the chosen one not there; `difference` is the interval of its held-out ghosting minus the
// chosen's (paired bootstrap), which holding 0 makes the two within noise of each other.
struct Recommendation {
    std::optional<std::size_t> chosen; // into the candidates; none where none qualifies
    std::string why;                   // the rule it won by, no final stop
    std::string noise; // sentences: its interval, and the runner-up within noise of it or not; empty with none
    std::optional<std::size_t> runner_up;
    Interval difference;
};

// What a candidate may cost: float ops or median ms (one of them, or neither).
struct Budget {
    std::optional<std::size_t> ops;
    std::optional<double> ms;
    bool admits(const Candidate& c) const { return (!ops || c.float_ops <= *ops) && (!ms || c.ms <= *ms); }
};

// The rule: with a target, the candidate of fewest float ops whose held-out ghosting is at most the
// target (of equal cost, the one that ghosts least); else the one of least held-out ghosting among
// those within the budget (any cost without one; of equal ghosting, the cheaper). Candidates with
// no held-out figure never qualify; the earliest of exact ties. `why` names the runner-up and
// whether it is within noise, and, with a target, whether the chosen one's interval reaches above it.
Recommendation recommend(const std::vector<Candidate>& candidates, const Budget& budget,
                         std::optional<double> target_ghosting);

// The candidates on the Pareto front of held-out ghosting against float ops: none both cheaper (or
// as cheap) and ghosting less (or as little), one strictly. Indices, cheapest first.
std::vector<std::size_t> pareto_front(const std::vector<Candidate>& candidates);

// A --sets file's set, as kdop.manifest's `set:` line names it where that set is recommended: a
// manifest reads set files only from its own folder and below (generator/manifest.h), so the file
// is copied beside it, as <set>.axes.
struct GivenSetFile {
    std::string given;     // the path --sets gave
    std::string text;      // what it holds, copied whole
    bool in_place = false; // it already is <out>/<set>.axes: nothing to copy
};

// Each candidate's ghosting_noise: within noise of the recommended candidate, or of the one of
// least held-out ghosting where none is recommended; its ms_noise: within noise of the fastest.
void mark_noise(std::vector<Candidate>& candidates, const Recommendation& recommendation);

struct ChooseResult {
    std::vector<Candidate> candidates; // the fitted ones first, then the built-in ones, each in spec order
    Recommendation recommendation;
    std::vector<std::pair<std::string, std::string>> fitted_files; // file name (fitted<N>.axes) and text
    std::vector<std::string> fit_sequences, validate_sequences;    // their names
    std::string held_out;                                          // what was held out, in words
    std::map<std::string, GivenSetFile> given_files;               // by set name: every --sets file's
    ColorRange range = ColorRange::ldr;                            // every sequence's, so every figure's FLIP mode
    bool upscaled = false;      // whether any sequence's frames are smaller than its outputs: the resolve upscaled
    BootstrapOptions bootstrap; // how the held-out ghosting's intervals were drawn
    Metrics metrics;            // what each candidate's figures are, by index: the evaluation's
    int ranks = 1;              // the ranks the candidates were measured over
};

// The run, on options that pass check(): checks (a usage Error where the command line is at fault:
// sequences of two color ranges, two candidates of one set name, a set
// file it would write over an input), fits, measures, recommends. Writes nothing. Under mpirun every rank checks, the
// fits are shared over the ranks as kdop optimize shares them (the same sets for any rank count), and so are the
// candidates' measurements, each rank its contiguous share (the same figures for any rank count); rank 0 alone times
// them, and on the other ranks the result holds the fitted files and no candidates.
Result<ChooseResult> choose(const Context& context, const ChooseOptions& options, const Ranks& ranks);

} // namespace kdop
