// Building variants into SPIR-V: every default variant validates and keeps no loop (checked here
// with SPIRV-Tools' own validator and disassembler, not the generator's checks), the interface is
// reflected, output is deterministic, identical modules are stored once, and compiler messages
// name the GLSL line.
#include "generator/glsl_compiler.h"
#include "generator/registry_writer.h"
#include "generator/spirv_module.h"
#include "generator/variant_builder.h"
#include "kdop_stripped_test_shaders.h"
#include "kdop_test_shaders.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>
#include <spirv-tools/libspirv.hpp>

namespace kdop {
namespace {

const std::vector<BuiltVariant>& default_variants() {
    static const auto built = [] {
        auto specs = select_variants({}, {}, {});
        EXPECT_TRUE(specs);
        auto result = build_variants(*specs);
        EXPECT_TRUE(result) << (result ? "" : result.error().message);
        return result ? *result : std::vector<BuiltVariant>{};
    }();
    return built;
}

TEST(SpirvBuild, EveryDefaultVariantValidatesAndHasNoLoop) {
    ASSERT_EQ(default_variants().size(), 24u);
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    std::string messages;
    tools.SetMessageConsumer(
        [&](spv_message_level_t, const char*, const spv_position_t&, const char* m) { messages += m; });
    for (const BuiltVariant& v : default_variants()) {
        SCOPED_TRACE(v.name);
        EXPECT_TRUE(tools.Validate(v.spirv)) << messages;
        std::string disassembly;
        ASSERT_TRUE(tools.Disassemble(v.spirv, &disassembly));
        EXPECT_EQ(disassembly.find("OpLoopMerge"), std::string::npos);
        // kdop's line information is gone (its bytes must not depend on file names or comments);
        // the names stay, as glslc keeps them.
        EXPECT_EQ(disassembly.find("OpLine"), std::string::npos);
        EXPECT_EQ(disassembly.find("OpString"), std::string::npos);
        EXPECT_EQ(disassembly.find("OpModuleProcessed"), std::string::npos);
        EXPECT_NE(disassembly.find("OpName %history_frame \"history_frame\""), std::string::npos) << disassembly;
        EXPECT_NE(disassembly.find("OpName %rectified_history \"rectified_history\""), std::string::npos);
        EXPECT_NE(disassembly.find("OpEntryPoint GLCompute"), std::string::npos);
        EXPECT_EQ(v.counts.loop_merges, 0u);
    }
}

TEST(SpirvBuild, StripNamesLeavesCodeOnlyAndTheSameCode) {
    auto specs = select_variants({"dop22"}, {"varclip"}, {"n5"});
    ASSERT_TRUE(specs);
    VariantSpec spec = specs->front();
    auto named = build_variant(spec);
    spec.strip_names = true;
    auto stripped = build_variant(spec);
    ASSERT_TRUE(named && stripped);
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    EXPECT_TRUE(tools.Validate(stripped->spirv));
    std::string named_text, stripped_text;
    ASSERT_TRUE(tools.Disassemble(named->spirv, &named_text, SPV_BINARY_TO_TEXT_OPTION_NONE));
    ASSERT_TRUE(tools.Disassemble(stripped->spirv, &stripped_text, SPV_BINARY_TO_TEXT_OPTION_NONE));
    EXPECT_NE(named_text.find("OpName"), std::string::npos);
    EXPECT_EQ(stripped_text.find("OpName"), std::string::npos);
    EXPECT_EQ(stripped_text.find("OpSource"), std::string::npos);
    // Names are all that differ: the function bodies are the same instructions.
    EXPECT_EQ(named->counts.function_instructions, stripped->counts.function_instructions);
    EXPECT_LT(stripped->spirv.size(), named->spirv.size());
}

TEST(SpirvBuild, KdopAddVariantsKeepsAProjectShadersNamesUnlessStripNames) {
    // tests/CMakeLists.txt builds examples/taa_resolve's shader twice, the second with STRIP_NAMES.
    auto disassemble = [](const Variant* v) {
        std::string text;
        spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
        EXPECT_TRUE(tools.Disassemble(std::vector<std::uint32_t>(v->spirv, v->spirv + v->spirv_word_count), &text));
        return text;
    };
    const Variant* named = test_shaders::variants().find("taa_resolve");
    const Variant* stripped = stripped_test_shaders::variants().find("taa_resolve");
    ASSERT_TRUE(named && stripped);
    const std::string named_text = disassemble(named), stripped_text = disassemble(stripped);
    EXPECT_NE(named_text.find("OpName %history_frame \"history_frame\""), std::string::npos) << named_text;
    EXPECT_NE(named_text.find("\"current_weight\""), std::string::npos) << "the push constant's member";
    EXPECT_EQ(stripped_text.find("OpName"), std::string::npos) << stripped_text;
    EXPECT_EQ(stripped_text.find("OpMemberName"), std::string::npos);
    // The registry's reflection does not depend on the names shipping.
    EXPECT_STREQ(stripped->bindings[1].name, "history_frame");
    EXPECT_STREQ(stripped->push_constants[0].name, named->push_constants[0].name);
}

TEST(SpirvBuild, MoreAxesCostMoreInstructions) {
    // A sanity check of the emitted code's scale, not a cost claim: per mode and neighborhood,
    // the instruction count rises with k (aabb < dop16 < dop22 < dop32).
    auto count = [](const std::string& name) {
        for (const BuiltVariant& v : default_variants())
            if (v.name == name) return v.counts.function_instructions;
        ADD_FAILURE() << name;
        return size_t{0};
    };
    for (std::string suffix : {"-clip-n9", "-varclip-n5"}) {
        EXPECT_LT(count("aabb" + suffix), count("dop16-grass" + suffix));
        EXPECT_LT(count("dop16-grass" + suffix), count("dop22" + suffix));
        EXPECT_LT(count("dop22" + suffix), count("dop32" + suffix));
    }
    EXPECT_LT(count("dop32-clip-n5"), count("dop32-clip-n9"));
}

TEST(SpirvBuild, ReflectsBindingsAndPushConstants) {
    for (const BuiltVariant& v : default_variants()) {
        SCOPED_TRACE(v.name);
        const ShaderInterface& i = v.interface;
        EXPECT_EQ(i.entry_point, "main");
        EXPECT_EQ(i.local_size, (std::array<std::uint32_t, 3>{8, 8, 1}));
        ASSERT_EQ(i.bindings.size(), 3u);
        EXPECT_EQ(i.bindings[0].name, "current_frame");
        EXPECT_EQ(i.bindings[0].type, DescriptorType::combined_image_sampler);
        EXPECT_EQ(i.bindings[1].name, "history_frame");
        EXPECT_EQ(i.bindings[1].type, DescriptorType::combined_image_sampler);
        EXPECT_EQ(i.bindings[2].name, "rectified_history");
        EXPECT_EQ(i.bindings[2].type, DescriptorType::storage_image);
        for (std::uint32_t b = 0; b < 3; ++b) EXPECT_EQ(i.bindings[b].binding, b);
        if (v.spec.mode == Mode::varclip) {
            ASSERT_EQ(i.push_constants.size(), 1u);
            EXPECT_EQ(i.push_constants[0].name, "gamma");
            EXPECT_EQ(i.push_constants[0].offset, 0u);
            EXPECT_EQ(i.push_constant_size, 4u);
        } else {
            EXPECT_TRUE(i.push_constants.empty());
            EXPECT_EQ(i.push_constant_size, 0u);
        }
    }
}

TEST(SpirvBuild, IsDeterministicAcrossRunsAndThreadCounts) {
    auto specs = select_variants({"dop32", "ycocg"}, {}, {});
    ASSERT_TRUE(specs);
    auto serial = build_variants(*specs, 1);
    auto parallel = build_variants(*specs, 4);
    ASSERT_TRUE(serial && parallel);
    ASSERT_EQ(serial->size(), parallel->size());
    for (size_t i = 0; i < serial->size(); ++i) {
        EXPECT_EQ((*serial)[i].name, (*parallel)[i].name);
        EXPECT_EQ((*serial)[i].spirv, (*parallel)[i].spirv) << (*serial)[i].name;
        EXPECT_EQ((*serial)[i].compute_glsl, (*parallel)[i].compute_glsl);
    }
    auto a = write_registry(*serial, "x", "x.h"), b = write_registry(*parallel, "x", "x.h");
    EXPECT_EQ(a.source, b.source);
    EXPECT_EQ(a.header, b.header);
}

TEST(SpirvBuild, RegistryStoresIdenticalModulesOnce) {
    // tiny-twin.axes holds the same axes as tiny.axes under another name: same code, same module.
    auto specs = select_variants({test::data_path("tiny.axes"), test::data_path("tiny-twin.axes")}, {"clip"}, {"n9"});
    ASSERT_TRUE(specs) << specs.error().message;
    auto built = build_variants(*specs);
    ASSERT_TRUE(built) << built.error().message;
    ASSERT_EQ(built->size(), 2u);
    EXPECT_EQ((*built)[0].spirv, (*built)[1].spirv);
    auto sources = write_registry(*built, "twins", "twins.h");
    EXPECT_NE(sources.source.find("// 1 distinct SPIR-V module;"), std::string::npos);
    EXPECT_NE(sources.source.find("const std::uint32_t spirv_0[]"), std::string::npos);
    EXPECT_EQ(sources.source.find("spirv_1"), std::string::npos);
}

TEST(SpirvBuild, CompilerErrorsNameTheGlslLine) {
    const std::string source =
        "#version 450\nlayout(local_size_x = 1) in;\nvoid main()\n{\n    float x = undefined_thing;\n}\n";
    auto result = compile_glsl_compute(source, "broken.comp");
    ASSERT_FALSE(result);
    EXPECT_NE(result.error().message.find("broken.comp:5: error: 'undefined_thing' : undeclared identifier"),
              std::string::npos)
        << result.error().message;
    EXPECT_NE(result.error().message.find("    float x = undefined_thing;"), std::string::npos)
        << result.error().message;
}

TEST(SpirvBuild, ValidatorMessagesMapToTheGlslLineOfTheInstruction) {
    // glslang's output carries OpLine; the instruction on line 5 of this shader is the store.
    const std::string source = "#version 450\nlayout(local_size_x = 1) in;\nvoid main()\n{\n    float x = 1.0;\n}\n";
    auto words = compile_glsl_compute(source, "ok.comp");
    ASSERT_TRUE(words) << words.error().message;
    bool found = false;
    for (const SpirvInstruction& inst : spirv_instructions(*words))
        if (inst.opcode == 62 /* OpStore */) {
            EXPECT_EQ(glsl_line_of_instruction(*words, inst.ordinal), 5);
            found = true;
        }
    EXPECT_TRUE(found);
}

} // namespace
} // namespace kdop
