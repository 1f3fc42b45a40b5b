#include "generator/unused_resources.h"

#include <fmt/format.h>

#include <algorithm>

namespace kdop {

std::vector<DeclaredResource> unused_resources(std::span<const DeclaredResource> declared,
                                               const ShaderInterface& reflected) {
    std::vector<DeclaredResource> out;
    for (const DeclaredResource& r : declared) {
        const bool kept =
            r.type ? std::ranges::any_of(reflected.bindings, [&](const BindingInfo& b) { return b.name == r.name; })
                   : reflected.push_constant_size > 0;
        if (!kept) out.push_back(r);
    }
    return out;
}

std::string unused_resource_warning(std::string_view file, std::string_view entry_point,
                                    const DeclaredResource& resource) {
    const std::string what = resource.type ? to_string(*resource.type) : "push-constant block";
    const std::string where =
        resource.binding ? fmt::format(" (set {}, binding {})", resource.set, *resource.binding) : "";
    const char* missing =
        resource.type ? "the reflection has no binding for it" : "the reflection has no push constants";
    return fmt::format("{}: warning: {} '{}'{} is not used by the entry point '{}', so it is not in the SPIR-V and "
                       "{}\n",
                       file, what, resource.name, where, entry_point, missing);
}

} // namespace kdop
