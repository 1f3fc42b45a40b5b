#include "temporal/own_resolve.h"

#include "core/read_file.h"
#include "temporal/taa_shader.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop {
namespace {

// FNV-1a 64, continued over `text` from `hash`: the SPIR-V's hash (generator/spirv_module.h)
// over bytes. A label for a report, not a security hash.
std::uint64_t fnv1a64(std::string_view text, std::uint64_t hash = 0xcbf29ce484222325ull) {
    for (unsigned char c : text) hash = (hash ^ c) * 0x100000001b3ull;
    return hash;
}

} // namespace

std::string OwnResolve::label() const { return fmt::format("{} (fnv1a64 {:016x})", shader.filename().string(), hash); }

bool OwnResolve::reads_depth() const {
    return std::any_of(bindings.resources.begin(), bindings.resources.end(),
                       [](const auto& r) { return r.second == ResourceRole::depth; });
}

Result<OwnResolve> load_own_resolve(const std::filesystem::path& shader, const std::filesystem::path& bindings,
                                    const std::string& hlsl_entry) {
    auto source = read_input_file(shader);
    if (!source) return std::unexpected(source.error());
    auto map_text = read_input_file(bindings);
    if (!map_text) return std::unexpected(map_text.error());
    auto map = parse_resolve_bindings(*map_text, bindings.string());
    if (!map) return std::unexpected(map.error());
    OwnResolve resolve{shader, hlsl_entry, std::move(*map), fnv1a64(*map_text, fnv1a64(*source))};
    return resolve;
}

Result<BoundOwnResolve> build_bound_resolve(const OwnResolve& resolve, const VariantSpec& spec) {
    auto shader = build_own_resolve(resolve.shader, spec, resolve.hlsl_entry);
    if (!shader) return std::unexpected(shader.error());
    // The registry form records a uniform block's size alone; its members come from the build.
    std::vector<UniformMember> members;
    for (const BindingInfo& b : (*shader)->built().interface.bindings)
        for (const BindingInfo::Member& m : b.members) members.push_back({b.name, m.name, m.offset, m.size});
    auto roles = kdop::bind(resolve.bindings, (*shader)->variant(), members); // not std::bind, found by ADL
    if (!roles) return std::unexpected(roles.error());
    return BoundOwnResolve{std::move(*shader), std::move(*roles)};
}

} // namespace kdop
