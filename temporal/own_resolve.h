// A renderer's own TAA or TAAU resolve, measured in place of kdop's (kdop taa --resolve): its
// compute shader, which includes the variant under test as "kdop_variant.glsl" (or .hlsl), and the
// map that declares what each of its resources, push-constant members and uniform-block members
// is (resolve_bindings.h). Built once per variant and bound by role; the TAA resolve
// (taa_resolve.h) then runs it as it runs kdop's, with the history kept on the device.
#pragma once

#include "core/result.h"
#include "generator/runnable_variant.h"
#include "generator/variant_spec.h"
#include "temporal/resolve_bindings.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace kdop {

struct OwnResolve {
    std::filesystem::path shader; // .comp, or .cs.hlsl with hlsl_entry
    std::string hlsl_entry = "main";
    ResolveBindings bindings; // its map, read
    std::uint64_t hash = 0;   // FNV-1a 64 of the shader's text, then the map's: which resolve was measured
    // "<shader's file name> (fnv1a64 <hash>)": how every output names the resolve.
    std::string label() const;
    // Whether the map gives a resource the depth role: the frames' depth is then read.
    bool reads_depth() const;
};

// The resolve in `shader` with the map in `bindings`. A file that cannot be read, or a map that
// does not parse, is refused naming it. Whether the two agree is checked when it is built.
Result<OwnResolve> load_own_resolve(const std::filesystem::path& shader, const std::filesystem::path& bindings,
                                    const std::string& hlsl_entry = "main");

// The resolve built around `spec` (taa_shader.h's build_own_resolve) and bound by its map: refused,
// naming the shader, the map and the resource, where they do not agree (resolve_bindings.h's bind).
struct BoundOwnResolve {
    std::unique_ptr<RunnableVariant> shader;
    BoundResolve roles; // points into *shader
};
Result<BoundOwnResolve> build_bound_resolve(const OwnResolve& resolve, const VariantSpec& spec);

} // namespace kdop
