// --target-env: a variant built for each Vulkan version declares that version's SPIR-V in its header
// and validates for that environment (checked with SPIRV-Tools directly, not the generator's
// checks), from GLSL and from HLSL; the default is Vulkan 1.0, byte for byte what is embedded.
#include "generator/runnable_variant.h"
#include "generator/target_env.h"
#include "generator/variant_builder.h"
#include "runtime/context.h"
#include "runtime/kernel.h"
#include "runtime/rectify_pass.h"

#include <gtest/gtest.h>
#include <kdop_builtin_variants.h>
#include <spirv-tools/libspirv.hpp>

namespace kdop {
namespace {

spv_target_env spirv_tools_env(TargetEnv env) {
    switch (env) {
    case TargetEnv::vulkan1_0: return SPV_ENV_VULKAN_1_0;
    case TargetEnv::vulkan1_1: return SPV_ENV_VULKAN_1_1;
    case TargetEnv::vulkan1_2: return SPV_ENV_VULKAN_1_2;
    case TargetEnv::vulkan1_3: return SPV_ENV_VULKAN_1_3;
    }
    return SPV_ENV_UNIVERSAL_1_0;
}

bool validates(const std::vector<std::uint32_t>& words, spv_target_env env, std::string& messages) {
    spvtools::SpirvTools tools(env);
    tools.SetMessageConsumer(
        [&](spv_message_level_t, const char*, const spv_position_t&, const char* m) { messages += m; });
    return tools.Validate(words);
}

VariantSpec spec_for(const std::string& name, TargetEnv env) {
    auto specs = select_variants({"dop32"}, {}, {});
    EXPECT_TRUE(specs);
    for (VariantSpec s : *specs)
        if (variant_name(s) == name) {
            s.target_env = env;
            return s;
        }
    ADD_FAILURE() << "no variant " << name;
    return {};
}

TEST(TargetEnv, NamesParseAndPrintBack) {
    for (TargetEnv env : kAllTargetEnvs) EXPECT_EQ(parse_target_env(to_string(env)), env);
    EXPECT_EQ(parse_target_env("vulkan1.4"), std::nullopt);
    EXPECT_EQ(parse_target_env("Vulkan1.0"), std::nullopt);
    EXPECT_EQ(spirv_version_word(TargetEnv::vulkan1_0), 0x00010000u);
    EXPECT_EQ(spirv_version_word(TargetEnv::vulkan1_1), 0x00010300u);
    EXPECT_EQ(spirv_version_word(TargetEnv::vulkan1_2), 0x00010500u);
    EXPECT_EQ(spirv_version_word(TargetEnv::vulkan1_3), 0x00010600u);
}

TEST(TargetEnv, EachEnvironmentsModuleDeclaresItsVersionAndValidatesForIt) {
    for (SourceLanguage language : {SourceLanguage::glsl, SourceLanguage::hlsl})
        for (TargetEnv env : kAllTargetEnvs)
            for (const char* name : {"dop32-varclip-n9", "dop32-clip-n5"}) {
                SCOPED_TRACE(std::string(name) + " for " + std::string(to_string(env)) +
                             (language == SourceLanguage::hlsl ? " from HLSL" : " from GLSL"));
                auto built = build_variant(spec_for(name, env), language);
                ASSERT_TRUE(built) << built.error().message;
                ASSERT_GE(built->spirv.size(), 5u);
                EXPECT_EQ(built->spirv[1], spirv_version_word(env));
                std::string messages;
                EXPECT_TRUE(validates(built->spirv, spirv_tools_env(env), messages)) << messages;
                // The version is real: a module for a later Vulkan is refused by Vulkan 1.0's validator.
                if (env != TargetEnv::vulkan1_0) {
                    messages.clear();
                    EXPECT_FALSE(validates(built->spirv, SPV_ENV_VULKAN_1_0, messages));
                }
            }
}

std::string disassembled(const std::vector<std::uint32_t>& words) {
    spvtools::SpirvTools tools(SPV_ENV_UNIVERSAL_1_6);
    std::string text;
    EXPECT_TRUE(tools.Disassemble(words, &text));
    return text;
}

// glslang writes SPIR-V 1.6's workgroup size as OpExecutionModeId LocalSizeId, which needs the
// maintenance4 feature; kdop writes the literals, as glslc does.
TEST(TargetEnv, AVulkan13ModuleWritesItsWorkgroupSizeAsLiterals) {
    for (SourceLanguage language : {SourceLanguage::glsl, SourceLanguage::hlsl}) {
        auto built = build_variant(spec_for("dop32-clip-n9", TargetEnv::vulkan1_3), language);
        ASSERT_TRUE(built) << built.error().message;
        const std::string text = disassembled(built->spirv);
        EXPECT_EQ(text.find("LocalSizeId"), std::string::npos) << text.substr(0, 600);
        EXPECT_NE(text.find("LocalSize 8 8 1"), std::string::npos) << text.substr(0, 600);
    }
}

// ... and such a module runs on a Vulkan 1.3 device with its default features, under the validation
// layer, without VUID-RuntimeSpirv-LocalSizeId-06434.
TEST(TargetEnvGpu, AVulkan13ModuleRunsWithDefaultFeatures) {
    auto context = Context::create({"", true, VK_API_VERSION_1_3});
    ASSERT_TRUE(context) << context.error().message;
    auto built = build_variant(spec_for("dop32-clip-n9", TargetEnv::vulkan1_3));
    ASSERT_TRUE(built) << built.error().message;
    const RunnableVariant variant(std::move(*built));
    auto kernel = Kernel::create(**context, variant.variant());
    ASSERT_TRUE(kernel) << kernel.error().message;
    auto pass = RectifyPass::create(**context, 16, 8, TextureFormat::rgba32f);
    ASSERT_TRUE(pass) << pass.error().message;
    const Image current(16, 8, {0.5f, 0.25f, 0.125f, 1}), history(16, 8, {1, 1, 1, 1});
    ASSERT_TRUE((*pass)->upload(current, history));
    ASSERT_TRUE((*pass)->dispatch(**kernel, 1.0f));
    auto out = (*pass)->download();
    ASSERT_TRUE(out) << out.error().message;
    for (int c = 0; c < 3; ++c) // a flat neighborhood clips to its color, within the hardened padding
        EXPECT_NEAR(out->at(3, 4)[c], current.at(3, 4)[c], 1e-5);
    EXPECT_TRUE((*context)->validation_messages().empty()) << (*context)->validation_messages().front();
}

TEST(TargetEnv, TheDefaultIsVulkan10AndWhatIsEmbedded) {
    auto specs = select_variants({"dop32", "aabb"}, {}, {});
    ASSERT_TRUE(specs);
    for (const VariantSpec& spec : *specs) {
        SCOPED_TRACE(variant_name(spec));
        EXPECT_EQ(spec.target_env, TargetEnv::vulkan1_0);
        auto built = build_variant(spec);
        ASSERT_TRUE(built) << built.error().message;
        const Variant* embedded = builtin::variants().find(variant_name(spec).c_str());
        ASSERT_NE(embedded, nullptr);
        EXPECT_EQ(built->spirv,
                  std::vector<std::uint32_t>(embedded->spirv, embedded->spirv + embedded->spirv_word_count));
        EXPECT_EQ(built->spirv[1], 0x00010000u);
    }
}

} // namespace
} // namespace kdop
