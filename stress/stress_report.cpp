#include "stress/stress_report.h"

#include "harness/declared_table.h"
#include "harness/printed_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <span>
#include <vector>

namespace kdop {
namespace {

std::string cell_text(const CheckResult& result) {
    std::string codes;
    for (Invariant i : kInvariants)
        if (result[i].violated) codes += invariant_code(i);
    return codes.empty() ? "ok" : codes;
}

std::string legend(const StressRun& run, bool markdown) {
    std::string out = markdown ? "\n| case | what it holds |\n|---|---|\n" : "\ncases:\n";
    for (std::size_t c = 0; c < run.cases.size(); ++c)
        out += markdown ? fmt::format("| {} | {} |\n", run.cases[c], run.case_descriptions[c])
                        : fmt::format("  {:>2} {:<20} {}\n", c + 1, run.cases[c], run.case_descriptions[c]);
    out += markdown ? "\n| code | invariant |\n|---|---|\n" : "invariants (a cell lists those that failed):\n";
    for (Invariant i : kInvariants)
        out += markdown
                   ? fmt::format("| {} | {}: {} |\n", invariant_code(i), invariant_name(i), invariant_description(i))
                   : fmt::format("  {} {:<9} {}\n", invariant_code(i), invariant_name(i), invariant_description(i));
    return out;
}

std::string summary(const StressRun& run) {
    const std::size_t cells = run.variants.size() * run.cases.size();
    const std::size_t failing = run.failing_cells();
    return failing ? fmt::format("{} of {} variant-case pairs broke an invariant.\n", failing, cells)
                   : fmt::format("All {} variant-case pairs kept every invariant.\n", cells);
}

} // namespace

std::string stress_table_text(const StressRun& run) {
    // Rows are variants (by index); cases are numbered columns as wide as their widest cell.
    std::size_t name_width = 7;
    for (const std::string& v : run.variants) name_width = std::max(name_width, v.size());
    PrintedColumns<std::size_t> columns{
        {"variant", -int(name_width), [&run](std::size_t v) { return run.variants[v]; }}};
    for (std::size_t c = 0; c < run.cases.size(); ++c) {
        std::size_t width = fmt::format("{}", c + 1).size();
        for (const auto& row : run.results) width = std::max(width, cell_text(row[c]).size());
        columns.push_back(
            {fmt::format("{}", c + 1), int(width), [&run, c](std::size_t v) { return cell_text(run.results[v][c]); }});
    }
    std::string out = printed_header(columns) + "\n";
    for (std::size_t v = 0; v < run.variants.size(); ++v) out += printed_row(columns, v) + "\n";
    return out + legend(run, false) + summary(run);
}

Table stress_table(const StressRun& run) {
    struct Cell {
        const std::string &variant, &case_name;
        const CheckResult& result;
    };
    DeclaredColumns<Cell> columns{
        {{"variant", "", Shown::text}, [](const Cell& c) { return Value(c.variant); }},
        {{"case", "", Shown::text}, [](const Cell& c) { return Value(c.case_name); }},
        {{"pixels", "", Shown::integer}, [](const Cell& c) { return Value(std::int64_t(c.result.pixels)); }}};
    for (Invariant i : kInvariants) {
        const std::string name = invariant_name(i);
        columns.push_back({{name + "_checked", "", Shown::integer},
                           [i](const Cell& c) { return Value(std::int64_t(c.result[i].checked)); }});
        columns.push_back({{name + "_violated", "", Shown::integer},
                           [i](const Cell& c) { return Value(std::int64_t(c.result[i].violated)); }});
        // N and D are yes/no; a distance exists only for the others, and only where checked.
        const bool distance = i != Invariant::finite && i != Invariant::defined;
        columns.push_back({{name + "_worst", "S", Shown::significant}, [i, distance](const Cell& c) {
                               return distance && c.result[i].checked > 0 ? Value(c.result[i].worst) : Value();
                           }});
    }
    std::vector<Cell> cells;
    for (std::size_t v = 0; v < run.variants.size(); ++v)
        for (std::size_t c = 0; c < run.cases.size(); ++c)
            cells.push_back({run.variants[v], run.cases[c], run.results[v][c]});
    return declared_table(columns, std::span<const Cell>(cells));
}

std::string stress_report_markdown(const StressRun& run, const RunMetadata& run_info, float gamma) {
    std::string out = "# kdop stress report\n\n" + metadata_markdown(run_info);
    out += fmt::format("- gamma (variance clips): {}; tolerance: {:g} of the pixel's magnitude S\n\n", gamma,
                       kStressTolerance);
    // The matrix of variants (rows, by index) x cases (columns).
    DeclaredColumns<std::size_t> columns{
        {{"variant", "", Shown::text}, [&run](std::size_t v) { return Value(run.variants[v]); }}};
    for (std::size_t c = 0; c < run.cases.size(); ++c)
        columns.push_back({{run.cases[c], "", Shown::text},
                           [&run, c](std::size_t v) { return Value(cell_text(run.results[v][c])); }});
    std::vector<std::size_t> variants(run.variants.size());
    for (std::size_t v = 0; v < variants.size(); ++v) variants[v] = v;
    out += summary(run) + "\n" + declared_table(columns, std::span<const std::size_t>(variants)).markdown();
    out += legend(run, true);
    // The largest distance seen per invariant, over all cells: how close the passing ones came.
    out += "\nLargest distance seen (units of S), over every variant and case:\n\n";
    for (Invariant i : {Invariant::segment, Invariant::inside, Invariant::range, Invariant::classify}) {
        double worst = 0;
        for (const auto& row : run.results)
            for (const CheckResult& r : row) worst = std::max(worst, r[i].worst);
        out += fmt::format("- {} ({}): {:.3g}\n", invariant_name(i), invariant_code(i), worst);
    }
    if (run.failing_cells()) {
        out += "\n## First violation of each failing cell\n\n";
        for (std::size_t v = 0; v < run.variants.size(); ++v)
            for (std::size_t c = 0; c < run.cases.size(); ++c)
                for (Invariant i : kInvariants) {
                    const InvariantTally& t = run.results[v][c][i];
                    if (t.violated)
                        out += fmt::format("- {} on {}, {} ({} of {} pixels): {}\n", run.variants[v], run.cases[c],
                                           invariant_name(i), t.violated, t.checked, t.example);
                }
    }
    return out;
}

} // namespace kdop
