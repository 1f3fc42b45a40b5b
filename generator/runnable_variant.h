// A variant built in-process (variant_builder.h) in the shape the runtime loads: a registry
// Variant that points into storage this object owns. `kdop stress` builds what it runs, so it can
// stress any selection (a user's own axis sets, the paper numerics), and the bench can time and
// count the paper numerics beside the embedded defaults.
#pragma once

#include "generator/variant_builder.h"

#include <kdop/variant.h>

#include <memory>
#include <string>
#include <vector>

namespace kdop {

class RunnableVariant {
public:
    explicit RunnableVariant(BuiltVariant built);
    RunnableVariant(const RunnableVariant&) = delete; // variant() points into this object
    RunnableVariant& operator=(const RunnableVariant&) = delete;

    const BuiltVariant& built() const { return built_; }
    const Variant& variant() const { return variant_; }

private:
    BuiltVariant built_;
    std::vector<DescriptorBinding> bindings_;
    std::vector<PushConstantMember> push_constants_;
    Variant variant_{};
};

} // namespace kdop
