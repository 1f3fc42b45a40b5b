#include "harness/gnuplot.h"

#include "harness/subprocess.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iterator>

namespace kdop {

std::string gnuplot_data(const std::vector<std::vector<std::string>>& table) {
    std::string out;
    for (const auto& row : table) {
        for (std::size_t i = 0; i < row.size(); ++i) out += (i ? " " : "") + row[i];
        out += "\n";
    }
    return out;
}

std::string gnuplot_number(double value) { return std::isfinite(value) ? fmt::format("{:.6g}", value) : "NaN"; }

std::string gnuplot_string(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        if (alnum || std::string_view(" .,:;()+=/_-").find(c) != std::string_view::npos)
            out += c;
        else
            out += fmt::format("\\{:03o}", byte);
    }
    return out + "\"";
}

std::string gnuplot_terminal(int width, int height) {
    return fmt::format("set terminal pngcairo noenhanced size {},{} font 'sans,10'\n", width, height);
}

namespace {
std::string chart_file(std::size_t index) { return fmt::format("chart-{}.png", index); }
} // namespace

std::string gnuplot_output(const std::filesystem::path& scratch, std::size_t index) {
    return fmt::format("set output {}\n", gnuplot_string((scratch / chart_file(index)).string()));
}

bool charts_available(bool wanted) {
    if (!wanted) return false;
    if (!find_program("gnuplot").empty()) return true;
    fmt::print(stderr, "warning: gnuplot not found in PATH (Debian: gnuplot-nox): the data and report are written "
                       "without charts\n");
    return false;
}

void warn_no_charts(const std::string& reason) { fmt::print(stderr, "warning: the charts are left out: {}\n", reason); }

Result<void> write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.close();
    if (!out) return fail(fmt::format("{}: cannot write", path.string()));
    return {};
}

Result<std::vector<OutputFile>> draw_charts(const std::string& script, const std::vector<std::string>& charts,
                                            const std::filesystem::path& scratch,
                                            const std::filesystem::path& out_dir) {
    const std::filesystem::path script_path = scratch / "charts.gp", log = scratch / "gnuplot.log";
    if (auto ok = write_text(script_path, script); !ok) return std::unexpected(ok.error());
    const std::filesystem::path gnuplot = find_program("gnuplot");
    if (gnuplot.empty()) return fail("gnuplot not found in PATH (Debian: gnuplot-nox)");
    auto status = run_program({gnuplot.string(), script_path.string()}, log);
    if (!status) return std::unexpected(status.error());
    if (*status != 0) return fail(fmt::format("gnuplot failed on {}:{}", script_path.string(), log_tail(log, 12)));

    std::vector<OutputFile> files;
    for (std::size_t i = 0; i < charts.size(); ++i) {
        const std::filesystem::path drawn = scratch / chart_file(i);
        std::ifstream in(drawn, std::ios::binary);
        if (!in) return fail(fmt::format("gnuplot did not write {} ({})", drawn.string(), charts[i]));
        files.push_back({out_dir / charts[i], std::string(std::istreambuf_iterator<char>(in), {})});
    }
    return files;
}

} // namespace kdop
