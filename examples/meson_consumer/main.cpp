// Prints what the registry kdop-gen wrote for this Meson project holds, and fails unless the
// project's resolve is in it as declared: a compute shader with two samplers, an rgba16f storage
// image and a push constant, beside dop22's clip variant.
#include "taa_kdop.h"

#include <cstdio>
#include <cstring>

int main() {
    const kdop::VariantList registry = taa_kdop::variants();
    for (const kdop::Variant& v : registry) {
        std::printf("%s: %s shader, %u binding(s), %zu SPIR-V words\n", v.name, kdop::to_string(v.stage),
                    v.binding_count, v.spirv_word_count);
        for (std::uint32_t i = 0; i < v.binding_count; ++i)
            std::printf("  set %u binding %u: %s (%s)\n", v.bindings[i].set, v.bindings[i].binding, v.bindings[i].name,
                        kdop::to_string(v.bindings[i].type));
    }
    const kdop::Variant* resolve = registry.find("taa_resolve");
    const kdop::Variant* clip = registry.find("dop22-clip-n9");
    if (!resolve || !clip) {
        std::fprintf(stderr, "the registry lacks taa_resolve or dop22-clip-n9\n");
        return 1;
    }
    const kdop::DescriptorBinding* output = nullptr;
    for (std::uint32_t i = 0; i < resolve->binding_count; ++i)
        if (std::strcmp(resolve->bindings[i].name, "resolved_frame") == 0) output = &resolve->bindings[i];
    const bool as_declared = resolve->stage == kdop::ShaderStage::compute && resolve->binding_count == 3 && output &&
                             output->binding == 2 && output->format == 97 /* VK_FORMAT_R16G16B16A16_SFLOAT */ &&
                             resolve->push_constant_size == 4 &&
                             std::strcmp(resolve->push_constants[0].name, "current_weight") == 0;
    std::printf("taa_resolve %s\n", as_declared ? "is reflected as declared" : "is NOT reflected as declared");
    return as_declared ? 0 : 1;
}
