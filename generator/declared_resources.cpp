#include "generator/declared_resources.h"

#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>

namespace kdop {
namespace {

// The descriptor type the SPIR-V would give `type`, as shader_reflection.cpp maps SPIRV-Cross's
// resources; none for what is no descriptor or one kdop does not reflect.
std::optional<DescriptorType> descriptor_type(const glslang::TType& type) {
    if (type.getBasicType() == glslang::EbtBlock)
        return type.getQualifier().storage == glslang::EvqBuffer ? DescriptorType::storage_buffer
                                                                 : DescriptorType::uniform_buffer;
    if (type.getBasicType() != glslang::EbtSampler) return std::nullopt;
    const glslang::TSampler& s = type.getSampler();
    if (s.isPureSampler()) return DescriptorType::sampler;
    if (s.isSubpass()) return std::nullopt; // an input attachment
    if (s.isImage()) return s.isBuffer() ? DescriptorType::storage_texel_buffer : DescriptorType::storage_image;
    if (s.isBuffer()) return DescriptorType::uniform_texel_buffer;
    return s.isCombined() ? DescriptorType::combined_image_sampler : DescriptorType::sampled_image;
}

std::optional<DeclaredResource> declared_resource(const glslang::TIntermSymbol& symbol) {
    const glslang::TType& type = symbol.getType();
    const glslang::TQualifier& q = type.getQualifier();
    if (q.storage != glslang::EvqUniform && q.storage != glslang::EvqBuffer) return std::nullopt;
    const bool block = type.getBasicType() == glslang::EbtBlock;
    // glslang names a block without an instance "anon@N"; the SPIR-V's variable then has no name,
    // and the reflection takes the block's.
    const glslang::TString& name =
        block && glslang::IsAnonymous(symbol.getName()) ? type.getTypeName() : symbol.getName();
    DeclaredResource out;
    out.name.assign(name.begin(), name.end());
    if (block && q.isPushConstant()) return out;
    out.type = descriptor_type(type);
    if (!out.type) return std::nullopt;
    if (q.hasBinding()) out.binding = q.layoutBinding;
    if (q.hasSet()) out.set = q.layoutSet;
    return out;
}

} // namespace

std::vector<DeclaredResource> declared_resources(const glslang::TIntermediate& ast) {
    // The tree's root is a sequence whose last node, EOpLinkerObjects, lists every global the stage
    // declares, used or not, each a symbol: what the SPIR-V generator starts from.
    std::vector<DeclaredResource> out;
    const TIntermNode* tree = ast.getTreeRoot();
    const glslang::TIntermAggregate* root = tree ? tree->getAsAggregate() : nullptr;
    if (!root) return out;
    for (const TIntermNode* node : root->getSequence()) {
        const glslang::TIntermAggregate* objects = node->getAsAggregate();
        if (!objects || objects->getOp() != glslang::EOpLinkerObjects) continue;
        for (const TIntermNode* object : objects->getSequence())
            if (const glslang::TIntermSymbol* symbol = object->getAsSymbolNode())
                if (auto resource = declared_resource(*symbol)) out.push_back(std::move(*resource));
    }
    return out;
}

} // namespace kdop
