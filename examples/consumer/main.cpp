// Lists the embedded variants and checks that one (argv[1], default dop22-clip-n9) is there with
// what a pipeline needs: SPIR-V, the descriptor bindings and the workgroup size; and prints the
// resolve the manifest records.
#include "consumer_kdop_variants.h"

#include <cstdio>

int main(int argc, char** argv) {
    const char* wanted = argc > 1 ? argv[1] : "dop22-clip-n9";
    for (const kdop::Variant& v : consumer_kdop::variants())
        std::printf("%s: %zu SPIR-V words, %u bindings, %u push-constant bytes, hash %016llx\n", v.name,
                    v.spirv_word_count, v.binding_count, v.push_constant_size,
                    static_cast<unsigned long long>(v.spirv_hash));

    const kdop::Variant* v = consumer_kdop::variants().find(wanted);
    if (!v) {
        std::fprintf(stderr, "variant %s is not embedded\n", wanted);
        return 1;
    }
    const bool usable = v->spirv_word_count > 5 && v->spirv[0] == 0x07230203u && v->binding_count == 3 &&
                        v->local_size[0] * v->local_size[1] * v->local_size[2] > 0;
    std::printf("found %s (%s, %u axes): %s\n", v->name, kdop::to_string(v->mode), v->axis_count,
                usable ? "usable" : "INCOMPLETE");
    // The resolve the manifest records, a constant of the header: build the resolve with it.
    constexpr kdop::ResolveSettings resolve = consumer_kdop::resolve_settings;
    static_assert(resolve.current_weight > 0 && resolve.current_weight <= 1, "a blend weight");
    std::printf("resolve: gamma %g, current weight %g, %s history\n", resolve.gamma, resolve.current_weight,
                kdop::to_string(resolve.history_filter));
    return usable ? 0 : 1;
}
