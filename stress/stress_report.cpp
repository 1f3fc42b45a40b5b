#include "stress/stress_report.h"

#include <fmt/format.h>

#include <algorithm>

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
    std::size_t name_width = 7;
    for (const std::string& v : run.variants) name_width = std::max(name_width, v.size());
    std::vector<std::size_t> widths;
    for (std::size_t c = 0; c < run.cases.size(); ++c) {
        std::size_t w = fmt::format("{}", c + 1).size();
        for (const auto& row : run.results) w = std::max(w, cell_text(row[c]).size());
        widths.push_back(w);
    }
    std::string out = fmt::format("{:<{}}", "variant", name_width);
    for (std::size_t c = 0; c < run.cases.size(); ++c) out += fmt::format(" {:>{}}", c + 1, widths[c]);
    out += "\n";
    for (std::size_t v = 0; v < run.variants.size(); ++v) {
        out += fmt::format("{:<{}}", run.variants[v], name_width);
        for (std::size_t c = 0; c < run.cases.size(); ++c)
            out += fmt::format(" {:>{}}", cell_text(run.results[v][c]), widths[c]);
        out += "\n";
    }
    return out + legend(run, false) + summary(run);
}

Table stress_table(const StressRun& run) {
    std::vector<Column> columns{
        {"variant", "", Shown::text}, {"case", "", Shown::text}, {"pixels", "", Shown::integer}};
    for (Invariant i : kInvariants) {
        const std::string name = invariant_name(i);
        columns.push_back({name + "_checked", "", Shown::integer});
        columns.push_back({name + "_violated", "", Shown::integer});
        columns.push_back({name + "_worst", "S", Shown::significant});
    }
    Table table(std::move(columns));
    for (std::size_t v = 0; v < run.variants.size(); ++v)
        for (std::size_t c = 0; c < run.cases.size(); ++c) {
            const CheckResult& r = run.results[v][c];
            std::vector<Value> row{run.variants[v], run.cases[c], std::int64_t(r.pixels)};
            for (Invariant i : kInvariants) {
                row.push_back(std::int64_t(r[i].checked));
                row.push_back(std::int64_t(r[i].violated));
                // N and D are yes/no; a distance exists only for the others, and only where checked.
                const bool measured = r[i].checked > 0 && i != Invariant::finite && i != Invariant::defined;
                row.push_back(measured ? Value(r[i].worst) : Value());
            }
            table.add(std::move(row));
        }
    return table;
}

std::string stress_report_markdown(const StressRun& run, const RunMetadata& run_info, float gamma) {
    std::string out = "# kdop stress report\n\n" + metadata_markdown(run_info);
    out += fmt::format("- gamma (variance clips): {}; tolerance: {:g} of the pixel's magnitude S\n\n", gamma,
                       kStressTolerance);
    // The matrix of variants x cases, as a table of text columns.
    std::vector<Column> columns{{"variant", "", Shown::text}};
    for (const std::string& c : run.cases) columns.push_back({c, "", Shown::text});
    Table matrix(std::move(columns));
    for (std::size_t v = 0; v < run.variants.size(); ++v) {
        std::vector<Value> row{run.variants[v]};
        for (const CheckResult& r : run.results[v]) row.push_back(cell_text(r));
        matrix.add(std::move(row));
    }
    out += summary(run) + "\n" + matrix.markdown();
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
