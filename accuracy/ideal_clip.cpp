#include "accuracy/ideal_clip.h"

#include "core/parallel_for.h"
#include "reference/cpu_clip.h"

#include <fmt/format.h>
#include <glpk.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <mutex>

namespace kdop {
namespace {

// Rows: 1-3 the color equation, 4 the weights' sum, 5 s + t. Columns: one weight per neighborhood
// color, then s, then t; all of them >= 0.
constexpr int kWeightRow = 4, kSegmentRow = 5;

// GLPK's rational simplex does not take a double as the rational it denotes: it replaces it with a
// nearby simpler fraction (set_d_eps in glpapi07.c, relative error up to 1e-9), except for integers,
// which it converts exactly. Scaling every color by one power of two changes no t (the LP is
// homogeneous in the colors) and is exact, so the colors are scaled until each is an integer.
// Returns the exponent, or nothing if the scaled colors would overflow (no float32 input comes near).
std::optional<int> integer_scale(std::span<const glm::dvec3> neighborhood, const glm::dvec3& current,
                                 const glm::dvec3& history) {
    int scale = 0, top = std::numeric_limits<int>::min();
    auto visit = [&](double v) {
        if (v == 0) return;
        int exponent;
        const double mantissa = std::frexp(std::abs(v), &exponent); // v = mantissa 2^exponent
        const auto bits = static_cast<std::uint64_t>(std::ldexp(mantissa, 53));
        scale = std::max(scale, 53 - exponent - std::countr_zero(bits)); // lowest set bit 2^-scale
        top = std::max(top, exponent);
    };
    for (const glm::dvec3& p : neighborhood) visit(p.x), visit(p.y), visit(p.z);
    for (const glm::dvec3* p : {&current, &history}) visit(p->x), visit(p->y), visit(p->z);
    if (top != std::numeric_limits<int>::min() && top + scale > std::numeric_limits<double>::max_exponent)
        return std::nullopt;
    return scale;
}

void set_column(glp_prob* lp, int column, const glm::dvec3& color, int unit_row) {
    const int rows[] = {0, 1, 2, 3, unit_row}; // GLPK's arrays start at index 1
    const double values[] = {0, color.x, color.y, color.z, 1};
    glp_set_mat_col(lp, column, 4, rows, values);
}

} // namespace

IdealClipper::IdealClipper() : lp_(glp_create_prob()) {
    glp_term_out(GLP_OFF); // GLPK would print a log of every solve
    glp_set_obj_dir(lp_, GLP_MAX);
    glp_add_rows(lp_, kSegmentRow);
    for (int row = 1; row <= 3; ++row) glp_set_row_bnds(lp_, row, GLP_FX, 0, 0);
    glp_set_row_bnds(lp_, kWeightRow, GLP_FX, 1, 1);
    glp_set_row_bnds(lp_, kSegmentRow, GLP_FX, 1, 1);
}

IdealClipper::~IdealClipper() { glp_delete_prob(lp_); }

std::optional<double> IdealClipper::exit(std::span<const glm::dvec3> neighborhood, const glm::dvec3& current,
                                         const glm::dvec3& history) {
    // Exact shortcuts for the commonest cases: the current color is one of the neighborhood's and
    // the history is the current color or another of them (a vertex of the hull).
    const auto listed = [&](const glm::dvec3& color) {
        return std::find(neighborhood.begin(), neighborhood.end(), color) != neighborhood.end();
    };
    if (listed(current) && (history == current || listed(history))) return 1.0;

    const int n = static_cast<int>(neighborhood.size());
    if (columns_ != n) { // a new neighborhood size: new weight columns
        if (const int old = glp_get_num_cols(lp_)) {
            std::vector<int> all(old + 1);
            for (int j = 1; j <= old; ++j) all[j] = j;
            glp_del_cols(lp_, old, all.data());
        }
        glp_add_cols(lp_, n + 2);
        for (int j = 1; j <= n + 2; ++j) glp_set_col_bnds(lp_, j, GLP_LO, 0, 0);
        glp_set_obj_coef(lp_, n + 2, 1); // maximize t
        columns_ = n;
    }
    const std::optional<int> scale = integer_scale(neighborhood, current, history);
    if (!scale) return std::numeric_limits<double>::quiet_NaN();
    const auto load = [&](int exponent) {
        const auto scaled = [&](const glm::dvec3& c) {
            return glm::dvec3(std::ldexp(c.x, exponent), std::ldexp(c.y, exponent), std::ldexp(c.z, exponent));
        };
        for (int i = 0; i < n; ++i) set_column(lp_, i + 1, scaled(neighborhood[i]), kWeightRow);
        set_column(lp_, n + 1, -scaled(current), kSegmentRow); // s
        set_column(lp_, n + 2, -scaled(history), kSegmentRow); // t
    };

    glp_smcp parameters;
    glp_init_smcp(&parameters);
    parameters.msg_lev = GLP_MSG_OFF;
    parameters.it_lim = 10000; // a few dozen pivots are typical; never loop forever
    // The floating-point simplex on the colors as they are finds a basis that is usually optimal
    // already (on the integer-scaled colors it would be badly conditioned); the rational simplex
    // then starts from it on the exact data and decides.
    load(0);
    glp_std_basis(lp_);
    glp_simplex(lp_, &parameters);
    load(*scale);
    if (glp_exact(lp_, &parameters) != 0) return std::numeric_limits<double>::quiet_NaN();
    switch (glp_get_status(lp_)) {
    case GLP_OPT: return std::clamp(glp_get_col_prim(lp_, n + 2), 0.0, 1.0);
    case GLP_NOFEAS: return std::nullopt;
    default: return std::numeric_limits<double>::quiet_NaN(); // cannot happen: t <= 1 bounds the LP
    }
}

Result<std::vector<double>> ideal_exits(const Image& current, const Image& history, Neighborhood shape) {
    const std::vector<glm::ivec2> offsets = reference_offsets(shape);
    std::vector<double> exits(current.pixels.size());
    std::mutex mutex;
    std::size_t first_failure = exits.size(); // the first pixel the LP failed on, in row order

    auto row = [&](std::size_t y) {
        IdealClipper clipper;
        std::vector<glm::dvec3> neighborhood(offsets.size());
        for (std::uint32_t x = 0; x < current.width; ++x) {
            gather_neighborhood(current, x, std::uint32_t(y), offsets, neighborhood);
            const std::optional<double> t =
                clipper.exit(neighborhood, glm::dvec3(current.at(x, y)), glm::dvec3(history.at(x, y)));
            exits[y * current.width + x] = t.value_or(std::numeric_limits<double>::quiet_NaN());
            if (!t || std::isnan(*t)) {
                std::lock_guard lock(mutex);
                first_failure = std::min(first_failure, y * current.width + x);
            }
        }
    };
    // GLPK keeps per-thread memory until glp_free_env, once the thread's problems are gone.
    parallel_for(current.height, 0, row, [] { glp_free_env(); });
    if (first_failure < exits.size())
        return fail(fmt::format("ideal clip: GLPK found no optimum at pixel ({}, {})", first_failure % current.width,
                                first_failure / current.width));
    return exits;
}

} // namespace kdop
