#include "tests/gpu_support.h"

#include <gtest/gtest.h>
#include <kdop_builtin_variants.h>

#include <glm/common.hpp>

#include <cmath>
#include <map>
#include <memory>

namespace kdop::test {

Context& gpu() {
    static auto context = Context::create({"", true});
    if (!context) {
        ADD_FAILURE() << "no Vulkan context: " << context.error().message;
        std::abort(); // every GPU test needs it; lavapipe is installed by install-deps.sh
    }
    return **context;
}

const Variant& builtin_variant(const std::string& name) {
    const Variant* v = builtin::variants().find(name.c_str());
    if (!v) {
        ADD_FAILURE() << "no built-in variant " << name;
        std::abort();
    }
    return *v;
}

DeviceRunner& runner() {
    static DeviceRunner instance(gpu());
    return instance;
}

VariantCatalog& catalog() {
    static VariantCatalog instance = *VariantCatalog::create({});
    return instance;
}

Image run_on_gpu(const Variant& variant, const Image& current, const Image& history, TextureFormat format,
                 float gamma) {
    Image out;
    const Variant* variants[] = {&variant};
    auto ran =
        runner().run(current, history, format, variants, gamma, [&](std::size_t, const Image& output) -> Result<void> {
            out = output;
            return {};
        });
    EXPECT_TRUE(ran) << ran.error().message;
    return out;
}

VariantSpec builtin_spec(const Variant& variant) {
    auto set = resolve_axis_set(variant.axis_set);
    EXPECT_TRUE(set) << set.error().message;
    return {set ? *set : AxisSet{}, variant.mode, variant.neighborhood, variant.form, variant.numerics};
}

ErrorReport relative_error(const Image& a, const Image& b, const Image& current, const Image& history) {
    ErrorReport report;
    for (std::uint32_t y = 0; y < a.height; ++y)
        for (std::uint32_t x = 0; x < a.width; ++x) {
            glm::vec3 d = glm::abs(glm::vec3(a.at(x, y)) - glm::vec3(b.at(x, y)));
            glm::vec3 c = glm::abs(glm::vec3(current.at(x, y))), h = glm::abs(glm::vec3(history.at(x, y)));
            double scale = std::max({1.0f, c.x, c.y, c.z, h.x, h.y, h.z});
            double e = std::max({d.x, d.y, d.z}) / scale;
            if (!(e <= report.max_relative)) { // also catches NaN
                report = {std::isnan(e) ? INFINITY : e, x, y};
                if (std::isnan(e)) return report;
            }
        }
    return report;
}

} // namespace kdop::test
