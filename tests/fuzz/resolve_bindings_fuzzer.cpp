// libFuzzer target: any bytes as a resolve's bindings map (kdop taa --resolve-bindings), read and
// then bound to a fixed reflection shaped as kdop's own upscaling resolve. Whatever is refused must
// be refused with a message that names the map, holds no raw control bytes and stays short;
// whatever is read gives each role to one name at most; whatever binds gives every resource and
// member of the shader one role, with the three a resolve needs among them. Any violation aborts,
// which libFuzzer reports.
#include "temporal/resolve_bindings.h"
#include "tests/fuzz/fuzz_checks.h"

#include <cstdint>
#include <set>
#include <string>
#include <string_view>

namespace {

using kdop::fuzz::require;

// The reflection of kdop's upscaling resolve, by hand: four textures, the output, four members.
const kdop::Variant& shader() {
    using kdop::DescriptorType;
    static const kdop::DescriptorBinding bindings[] = {
        {0, 0, DescriptorType::combined_image_sampler, "color_frame", 1, 32, 0, 0},
        {0, 1, DescriptorType::combined_image_sampler, "history_frame", 1, 32, 0, 0},
        {0, 2, DescriptorType::combined_image_sampler, "motion_frame", 1, 32, 0, 0},
        {0, 4, DescriptorType::storage_image, "rectified_history", 1, 32, 0, 109},
    };
    static const kdop::PushConstantMember members[] = {
        {"current_weight", 0, 4}, {"gamma", 4, 4}, {"jitter", 8, 8}, {"sample_distance", 16, 4}};
    static kdop::Variant v = [] {
        kdop::Variant s{};
        s.name = "taa-resolve";
        s.bindings = bindings, s.binding_count = 4;
        s.push_constants = members, s.push_constant_count = 4, s.push_constant_size = 20;
        return s;
    }();
    return v;
}

void require_message(const std::string& message) {
    kdop::fuzz::require_refusal_message(message, "map.json", "map.json");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto map = kdop::parse_resolve_bindings(text, "map.json");
    if (!map) {
        require_message(map.error().message);
        return 0;
    }
    std::set<int> roles;
    for (const auto& [name, role] : map->resources)
        require(roles.insert(int(role)).second, "a resource role given twice", name);
    roles.clear();
    for (const auto& [name, role] : map->push_constants)
        require(roles.insert(int(role)).second, "a push-constant role given twice", name);
    auto bound = kdop::bind(*map, shader());
    if (!bound) {
        require_message(bound.error().message);
        return 0;
    }
    require(bound->resources.size() == shader().binding_count, "a resource bound twice or not at all", "");
    require(bound->values.size() == shader().push_constant_count, "a member filled twice or not at all", "");
    for (auto role : {kdop::ResourceRole::current, kdop::ResourceRole::history, kdop::ResourceRole::output})
        require(bound->find(role) != nullptr, "a resolve bound without a role it needs", kdop::to_string(role));
    return 0;
}
