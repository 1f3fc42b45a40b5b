#include "optimize/fit_data.h"

#include "core/input_files.h"
#include "core/memory_budget.h"
#include "core/parallel_for.h"
#include "harness/progress.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <span>

namespace kdop {
namespace {

// Every rank's drawn neighborhoods to every rank, so each holds the whole sample.
void share_sample(const Ranks& ranks, NeighborhoodSampler& sampler, std::size_t frames) {
    std::vector<std::size_t> per_frame;
    for (std::size_t f = 0; f < frames; ++f) per_frame.push_back(sampler.drawn_points(f) * 3);
    std::vector<double> all;
    for (std::size_t f = 0; f < frames; ++f) {
        std::vector<glm::dvec3>& drawn = sampler.drawn(f);
        drawn.resize(per_frame[f] / 3); // another rank's frame: zeros until gathered
        for (const glm::dvec3& p : drawn) all.insert(all.end(), {p.x, p.y, p.z});
    }
    ranks.all_gather(all, per_frame);
    const double* at = all.data();
    for (std::size_t f = 0; f < frames; ++f)
        for (glm::dvec3& p : sampler.drawn(f)) p = glm::dvec3(at[0], at[1], at[2]), at += 3;
}

// The inputs' headers, and what refuses them before any pixel is read.
Result<FitInputs> read_inputs(const FitDataOptions& o, const Ranks& ranks) {
    auto read = fit_inputs(o.input);
    if (!read) return fail(read.error().message);
    if (!o.out.empty())
        if (auto ok = check_not_an_input(o.out, "--out", read->paths); !ok) return std::unexpected(ok.error());
    // Each rank reads and evaluates whole frames: the sums of a frame are the unit whose fixed
    // order makes the result the same for any rank count.
    if (std::size_t(ranks.size()) > read->frames.size())
        return usage_fail(fmt::format("mpirun -np {}: {} ranks share {} frame{}; give at most as many ranks as "
                                      "frames",
                                      ranks.size(), ranks.size(), read->frames.size(),
                                      read->frames.size() == 1 ? "" : "s"));
    // A frame's neighborhoods are gathered whole, held or not: refused up front if the largest
    // frame's would not fit, rather than failing to allocate after minutes of reading.
    std::uint64_t largest = 0;
    for (const FitFrame& frame : read->frames)
        largest = std::max(largest, neighborhood_bytes(frame.pixels, o.neighborhood));
    if (auto ok = check_memory("the neighborhoods of the largest frame", largest); !ok) return fail(ok.error().message);
    return read;
}

// This rank's share of the frames, read once: their neighborhoods and, with a sample, the sample.
Result<void> read_frames(const FitDataOptions& o, const Ranks& ranks, FitData& data) {
    // Held between passes while they take at most --memory MB (by default half what is
    // available); the frames beyond are read and gathered again on each pass. With --sample the
    // search passes over the sample alone, and every frame is read again only for the few scores
    // on all of them: by default none is held, so memory is the sample's and one frame's,
    // whatever the frame count.
    const std::uint64_t budget = o.memory   ? std::uint64_t(*o.memory * 1024 * 1024)
                                 : o.sample ? 0
                                            : (available_memory() ? available_memory() / 2 : std::uint64_t(4) << 30);
    const std::vector<FitFrame>& frames = data.inputs.frames;
    std::vector<std::uint64_t> pixels;
    for (const FitFrame& frame : frames) pixels.push_back(frame.pixels);
    std::optional<NeighborhoodSampler> sampler;
    if (o.sample) sampler.emplace(o.neighborhood, pixels, *o.sample, o.seed);
    const auto [first, end] = ranks.share(frames.size());
    FrameShare share{first, end, {}};
    if (ranks.size() > 1)
        share.share = [&ranks](std::span<double> sums, std::size_t per_frame) {
            ranks.all_gather(sums, std::vector<std::size_t>(sums.size() / per_frame, per_frame));
        };
    Progress progress(ranks.size() > 1 ? fmt::format("reading frames on rank 0 of {}", ranks.size())
                                       : std::string("reading frames"),
                      end - first);
    auto gathered =
        FrameNeighborhoods::gather(frames, o.neighborhood, budget, share, [&](std::size_t frame, const Image& image) {
            if (sampler) sampler->add(frame, image);
            progress.advance(frames[frame].label);
        });
    progress.finish();
    // A frame that a rank could not read stops every rank, with its error, before any output.
    if (auto ok = ranks.agree(gathered ? Result<void>{} : std::unexpected(gathered.error())); !ok)
        return fail(ok.error().message);
    data.neighborhoods = std::move(*gathered);
    if (sampler) {
        if (ranks.size() > 1) share_sample(ranks, *sampler, frames.size());
        data.sampled.emplace(sampler->finish());
    }
    return {};
}

} // namespace

Result<FitData> read_fit_data(const FitDataOptions& o, const Ranks& ranks,
                              const std::function<Result<void>()>& before_frames) {
    FitData data;
    auto inputs = read_inputs(o, ranks);
    if (!inputs) return std::unexpected(inputs.error());
    data.inputs = std::move(*inputs);
    if (before_frames)
        if (auto ok = before_frames(); !ok) return std::unexpected(ok.error());
    if (auto ok = read_frames(o, ranks, data); !ok) return std::unexpected(ok.error());
    return data;
}

unsigned rank_threads(unsigned threads) {
    if (const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE"); local && threads == 0)
        return std::max(1u, core_count() / unsigned(std::max(1, std::atoi(local))));
    return threads;
}

std::string fit_objective(const FitData& data, Neighborhood shape, const ColorMap& color_map) {
    if (!data.neighborhoods) return "volume of the k-DOP around the unit sphere";
    const std::string in_space =
        color_map.kind == ColorMap::Kind::linear ? "" : fmt::format(", in {} space", to_string(color_map));
    return fmt::format("mean k-DOP volume over all {} {} neighborhoods of {}{}", data.neighborhoods->count(),
                       shape == Neighborhood::n9 ? "3x3" : "plus-shaped", data.inputs.description, in_space);
}

} // namespace kdop
