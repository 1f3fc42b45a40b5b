// Building variants from their HLSL: every built-in variant (both forms, both numerics' defaults,
// the baselines) compiles through glslang's HLSL front end, validates with SPIRV-Tools' own
// validator, keeps no loop, binds what the GLSL build binds, and compiles to the same float
// arithmetic as the GLSL build: the evidence, short of running them (gpu_hlsl_test.cpp), that the
// two languages' functions compute alike. Compiler messages name the HLSL line.
#include "generator/glsl_compiler.h"
#include "generator/spirv_cost.h"
#include "generator/spirv_module.h"
#include "generator/variant_builder.h"

#include <gtest/gtest.h>
#include <kdop_builtin_variants.h>
#include <spirv-tools/libspirv.hpp>

namespace kdop {
namespace {

const std::vector<BuiltVariant>& hlsl_builtin_variants() {
    static const auto built = [] {
        auto result = build_variants(all_builtin_variants(), 0, {}, SourceLanguage::hlsl);
        EXPECT_TRUE(result) << (result ? "" : result.error().message);
        return result ? *result : std::vector<BuiltVariant>{};
    }();
    return built;
}

TEST(HlslBuild, EveryBuiltinVariantValidatesAndHasNoLoop) {
    ASSERT_EQ(hlsl_builtin_variants().size(), all_builtin_variants().size());
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    std::string messages;
    tools.SetMessageConsumer(
        [&](spv_message_level_t, const char*, const spv_position_t&, const char* m) { messages += m; });
    for (const BuiltVariant& v : hlsl_builtin_variants()) {
        SCOPED_TRACE(v.name);
        EXPECT_FALSE(v.compute_hlsl.empty());
        EXPECT_TRUE(v.compute_glsl.empty()) << "built from HLSL only";
        EXPECT_TRUE(tools.Validate(v.spirv)) << messages;
        std::string disassembly;
        ASSERT_TRUE(tools.Disassemble(v.spirv, &disassembly));
        EXPECT_EQ(disassembly.find("OpLoopMerge"), std::string::npos);
        EXPECT_NE(disassembly.find("OpEntryPoint GLCompute"), std::string::npos);
    }
}

// Every arithmetic category matches exactly. Selects may not: glslang writes a GLSL `?:` whose
// operands are not simple values as a branch and an OpPhi, and an HLSL one (both sides evaluated,
// as HLSL defines it) as OpSelect; the values chosen between are the same.
TEST(HlslBuild, SameFloatArithmeticAsTheGlslBuild) {
    for (const BuiltVariant& v : hlsl_builtin_variants()) {
        SCOPED_TRACE(v.name);
        const Variant* glsl = builtin::variants().find(v.name.c_str());
        ASSERT_NE(glsl, nullptr);
        const FloatOps h = count_float_ops(v.spirv), g = count_float_ops({glsl->spirv, glsl->spirv_word_count});
        EXPECT_EQ(h.mul, g.mul);
        EXPECT_EQ(h.add_sub, g.add_sub);
        EXPECT_EQ(h.fma, g.fma);
        EXPECT_EQ(h.min_max, g.min_max);
        EXPECT_EQ(h.div, g.div);
        EXPECT_GE(h.compare_select, g.compare_select);
        EXPECT_EQ(h.other, g.other);
    }
}

// The HLSL build binds what the GLSL one does, so the runtime (and a renderer) can use either.
TEST(HlslBuild, InterfaceIsTheGlslVariants) {
    for (const BuiltVariant& v : hlsl_builtin_variants()) {
        SCOPED_TRACE(v.name);
        const Variant* glsl = builtin::variants().find(v.name.c_str());
        ASSERT_NE(glsl, nullptr);
        const ShaderInterface& i = v.interface;
        EXPECT_EQ(i.entry_point, glsl->entry_point);
        EXPECT_EQ(i.local_size,
                  (std::array<std::uint32_t, 3>{glsl->local_size[0], glsl->local_size[1], glsl->local_size[2]}));
        ASSERT_EQ(i.bindings.size(), glsl->binding_count);
        for (std::uint32_t b = 0; b < glsl->binding_count; ++b) {
            EXPECT_EQ(i.bindings[b].set, glsl->bindings[b].set);
            EXPECT_EQ(i.bindings[b].binding, glsl->bindings[b].binding);
            EXPECT_EQ(i.bindings[b].type, glsl->bindings[b].type) << "binding " << b;
            EXPECT_EQ(i.bindings[b].name, glsl->bindings[b].name);
        }
        ASSERT_EQ(i.push_constants.size(), glsl->push_constant_count);
        for (std::uint32_t p = 0; p < glsl->push_constant_count; ++p) {
            EXPECT_EQ(i.push_constants[p].name, glsl->push_constants[p].name);
            EXPECT_EQ(i.push_constants[p].offset, glsl->push_constants[p].offset);
            EXPECT_EQ(i.push_constants[p].size, glsl->push_constants[p].size);
        }
        EXPECT_EQ(i.push_constant_size, glsl->push_constant_size);
    }
}

TEST(HlslBuild, CompilerErrorsNameTheHlslLine) {
    const std::string source = "[numthreads(1, 1, 1)]\nvoid main()\n{\n    float3 x = undeclared;\n}\n";
    auto result = compile_hlsl_compute(source, "broken.hlsl");
    ASSERT_FALSE(result);
    EXPECT_NE(result.error().message.find("broken.hlsl:4: error:"), std::string::npos) << result.error().message;
    EXPECT_NE(result.error().message.find("    float3 x = undeclared;"), std::string::npos) << result.error().message;
}

} // namespace
} // namespace kdop
