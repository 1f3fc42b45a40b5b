#include "bench/cost_csv.h"

#include "harness/csv_reader.h"

#include <fmt/format.h>

#include <cstdlib>

namespace kdop {

Result<std::map<VariantKey, LavapipeCost>> read_bench_costs(const std::filesystem::path& path) {
    auto csv = read_csv(path);
    if (!csv) return fail("--cost: " + csv.error().message);
    const int variant = csv->column("variant"), instr = csv->column("instr_per_px"),
              marginal = csv->column("marginal_ms");
    if (variant < 0 || instr < 0 || marginal < 0)
        return fail(
            fmt::format("{}:1: not a kdop bench cost.csv (needs the columns variant, instr_per_px and marginal_ms)",
                        path.string()));
    struct Raw {
        double instr, marginal_ms;
    };
    std::map<VariantKey, Raw> raw;
    for (std::size_t r = 0; r < csv->rows.size(); ++r) {
        const std::vector<std::string>& f = csv->rows[r];
        const std::string where = fmt::format("{}:{}", path.string(), csv->lines[r]);
        const auto value = [&](int i) -> Result<double> {
            if (f[i].empty()) return NAN; // not measured
            char* end = nullptr;
            const double v = std::strtod(f[i].c_str(), &end);
            if (end != f[i].c_str() + f[i].size())
                return fail(fmt::format("{}: {} is '{}', not a number", where, csv->header[i], f[i]));
            return v;
        };
        auto key = parse_variant_key(f[variant], where);
        if (!key) return std::unexpected(key.error());
        auto i = value(instr);
        if (!i) return std::unexpected(i.error());
        auto m = value(marginal);
        if (!m) return std::unexpected(m.error());
        raw[*key] = {*i, *m};
    }
    std::map<VariantKey, LavapipeCost> costs;
    for (const auto& [key, r] : raw) {
        if (!key.is_clip()) continue;
        const auto gather = raw.find(gather_key(key.neighborhood));
        costs[key] = {gather == raw.end() ? NAN : r.instr - gather->second.instr, r.marginal_ms};
    }
    return costs;
}

} // namespace kdop
