#include "generator/runnable_variant.h"

namespace kdop {

RunnableVariant::RunnableVariant(BuiltVariant built) : built_(std::move(built)) {
    const ShaderInterface& interface = built_.interface;
    for (const BindingInfo& b : interface.bindings)
        bindings_.push_back({b.set, b.binding, b.type, b.name.c_str(), b.count, vulkan_stage_bit(interface.stage),
                             b.block_size, b.format});
    for (const PushConstantInfo& p : interface.push_constants)
        push_constants_.push_back({p.name.c_str(), p.offset, p.size});
    const VariantSpec& spec = built_.spec;
    variant_.name = built_.name.c_str();
    variant_.axis_set = spec.set.name.c_str();
    variant_.mode = spec.mode;
    variant_.neighborhood = spec.neighborhood;
    variant_.form = spec.form;
    variant_.numerics = spec.numerics;
    variant_.axis_count = static_cast<std::uint32_t>(spec.set.axes.size());
    variant_.spirv = built_.spirv.data();
    variant_.spirv_word_count = built_.spirv.size();
    variant_.spirv_hash = spirv_hash(built_.spirv);
    variant_.entry_point = interface.entry_point.c_str();
    for (int i = 0; i < 3; ++i) variant_.local_size[i] = interface.local_size[i];
    variant_.bindings = bindings_.data();
    variant_.binding_count = static_cast<std::uint32_t>(bindings_.size());
    variant_.push_constants = push_constants_.empty() ? nullptr : push_constants_.data();
    variant_.push_constant_count = static_cast<std::uint32_t>(push_constants_.size());
    variant_.push_constant_size = interface.push_constant_size;
    variant_.stage = interface.stage;
    variant_.color_output_count = interface.color_output_count;
}

} // namespace kdop
