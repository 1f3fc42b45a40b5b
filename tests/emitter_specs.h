// Variant specs the emitter tests share: the tiny test set's, and every built-in variant in both
// numerics, for the tests that compare one language's function with another's.
#pragma once

#include "generator/variant_spec.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <vector>

namespace kdop::test {

// A variant of tests/data/tiny.axes.
inline VariantSpec tiny_spec(Mode mode, Neighborhood n) {
    auto set = resolve_axis_set(data_path("tiny.axes"));
    EXPECT_TRUE(set) << set.error().message;
    return {*set, mode, n};
}

// Every built-in variant, and each clip and variance clip with the paper's numerics too.
inline std::vector<VariantSpec> builtin_variants_in_both_numerics() {
    std::vector<VariantSpec> specs = all_builtin_variants();
    const std::size_t builtin = specs.size();
    for (std::size_t i = 0; i < builtin; ++i)
        if (specs[i].mode == Mode::clip || specs[i].mode == Mode::varclip) {
            VariantSpec paper = specs[i];
            paper.numerics = Numerics::paper;
            specs.push_back(paper);
        }
    return specs;
}

} // namespace kdop::test
