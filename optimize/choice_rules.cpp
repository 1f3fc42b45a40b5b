// kdop choose's rule (optimize/choose.h): the candidate it recommends under a budget or a ghosting
// target, the runner-up and whether it is within noise, the candidates within noise of the pick,
// and the Pareto front of held-out ghosting against cost.
#include "optimize/choose.h"

#include "bench/cost_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace kdop {

namespace {

// The candidate the rule picks among those not `excluded` (recommend's rule), or none.
std::optional<std::size_t> best_candidate(const std::vector<Candidate>& candidates, const Budget& budget,
                                          std::optional<double> target_ghosting,
                                          std::optional<std::size_t> excluded = std::nullopt) {
    std::optional<std::size_t> best;
    auto better = [&](const Candidate& c, const Candidate& b) {
        if (target_ghosting)
            return c.float_ops < b.float_ops || (c.float_ops == b.float_ops && c.ranked() < b.ranked());
        return c.ranked() < b.ranked() || (c.ranked() == b.ranked() && c.float_ops < b.float_ops);
    };
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const Candidate& c = candidates[i];
        if (i == excluded || std::isnan(c.ranked())) continue;
        if (target_ghosting && !(c.ranked() <= *target_ghosting)) continue;
        if (!target_ghosting && !budget.admits(c)) continue;
        if (!best || better(c, candidates[*best])) best = i;
    }
    return best;
}

// To 4 decimals, as every ghosting is shown; a difference that rounds to 0 is 0, not -0.0000.
std::string shown_figure(double x) {
    const std::string text = fmt::format("{:.4f}", x);
    return text == "-0.0000" ? text.substr(1) : text;
}
std::string shown_interval(const Interval& i) {
    return fmt::format("[{}, {}]", shown_figure(i.low), shown_figure(i.high));
}

// What the frames say of the chosen candidate against the runner-up, and of the target.
std::string noise_sentences(const std::vector<Candidate>& candidates, const Recommendation& r,
                            std::optional<double> target_ghosting) {
    const Candidate& c = candidates[*r.chosen];
    if (!c.interval.known())
        return "The held-out frames are too few for an interval (each held-out sequence needs two bootstrap "
               "blocks of frames), so nothing says whether another candidate is within noise of it.";
    std::string text =
        fmt::format("Its held-out ghosting's {:.0f}% interval is {}.", 100 * kChoiceLevel, shown_interval(c.interval));
    if (target_ghosting && c.interval.high > *target_ghosting)
        text += fmt::format(" That interval reaches above the target {:.4g}: on other frames like these it may "
                            "miss it.",
                            *target_ghosting);
    if (!r.runner_up) return text + " No other candidate qualifies.";
    const Candidate& next = candidates[*r.runner_up];
    if (r.difference.holds(0))
        return text + fmt::format(" The runner-up, {}, ghosts {:.4f}, within noise of it: their paired "
                                  "difference's {:.0f}% interval, {}, holds 0, so the held-out frames do not tell "
                                  "the two apart.",
                                  next.key.name(), next.ranked(), 100 * kChoiceLevel, shown_interval(r.difference));
    return text + fmt::format(" The runner-up, {}, ghosts {:.4f}, beyond noise: their paired difference's {:.0f}% "
                              "interval, {}, does not hold 0.",
                              next.key.name(), next.ranked(), 100 * kChoiceLevel, shown_interval(r.difference));
}

} // namespace

Recommendation recommend(const std::vector<Candidate>& candidates, const Budget& budget,
                         std::optional<double> target_ghosting) {
    const std::optional<std::size_t> best = best_candidate(candidates, budget, target_ghosting);
    Recommendation r{best, {}, {}, {}, {}};
    const std::string within = budget.ops  ? fmt::format("at most {} float ops", *budget.ops)
                               : budget.ms ? fmt::format("at most {:.3g} ms (median)", *budget.ms)
                                           : std::string();
    if (!best) {
        r.why = target_ghosting
                    ? fmt::format("no candidate's held-out ghosting reaches the target {:.4g}", *target_ghosting)
                    : fmt::format("no candidate's clip costs {}", within);
        return r;
    }
    const Candidate& c = candidates[*best];
    r.runner_up = best_candidate(candidates, budget, target_ghosting, best);
    if (r.runner_up)
        r.difference = difference_interval(candidates[*r.runner_up].replicates, c.replicates, kChoiceLevel);
    const std::string costs = fmt::format("{} float ops, {:.3f} ms", c.float_ops, c.ms);
    r.why =
        target_ghosting ? fmt::format("the cheapest candidate ({}) whose held-out ghosting, {:.4f}, reaches the "
                                      "target {:.4g}",
                                      costs, c.ranked(), *target_ghosting)
        : !within.empty()
            ? fmt::format("the least held-out ghosting, {:.4f}, of the candidates whose clip costs {} (it costs {})",
                          c.ranked(), within, costs)
            : fmt::format("the least held-out ghosting, {:.4f}, of every candidate (no budget given; it costs {})",
                          c.ranked(), costs);
    r.noise = noise_sentences(candidates, r, target_ghosting);
    return r;
}

void mark_noise(std::vector<Candidate>& candidates, const Recommendation& recommendation) {
    std::optional<std::size_t> reference = recommendation.chosen;
    if (!reference)
        for (std::size_t i = 0; i < candidates.size(); ++i)
            if (!std::isnan(candidates[i].ranked()) &&
                (!reference || candidates[i].ranked() < candidates[*reference].ranked()))
                reference = i;
    const Candidate* fastest = nullptr;
    for (const Candidate& c : candidates)
        if (std::isfinite(c.ms) && (!fastest || c.ms < fastest->ms)) fastest = &c;
    for (Candidate& c : candidates) {
        c.ms_noise = fastest && std::isfinite(c.ms) &&
                     bench::within_noise({c.ms, c.ms_q1, c.ms_q3}, {fastest->ms, fastest->ms_q1, fastest->ms_q3});
        c.within_noise.reset();
        if (!reference) continue;
        const Interval difference = difference_interval(c.replicates, candidates[*reference].replicates, kChoiceLevel);
        if (difference.known()) c.within_noise = difference.holds(0);
    }
}

std::vector<std::size_t> pareto_front(const std::vector<Candidate>& candidates) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < candidates.size(); ++i)
        if (!std::isnan(candidates[i].ranked())) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const Candidate &x = candidates[a], &y = candidates[b];
        return x.float_ops < y.float_ops || (x.float_ops == y.float_ops && x.ranked() < y.ranked());
    });
    // Cheapest first: each candidate on the front ghosts strictly less than every cheaper one.
    std::vector<std::size_t> front;
    double least = INFINITY;
    for (std::size_t i : order)
        if (candidates[i].ranked() < least) {
            front.push_back(i);
            least = candidates[i].ranked();
        }
    return front;
}

} // namespace kdop
