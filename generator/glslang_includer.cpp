#include "generator/glslang_includer.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace kdop {

glslang::TShader::Includer::IncludeResult* GlslangIncluder::includeLocal(const char* header, const char* includer,
                                                                         size_t depth) {
    // glslang gives 1 for an include in the shader itself: chain_ holds the files above this one.
    const std::string includer_name = names_.real(includer);
    if (depth == 1) chain_.assign(1, includer_name);
    chain_.resize(std::min(chain_.size(), depth));
    if (!too_much_.empty()) // an empty text costs glslang nothing and adds no message per include
        return unread();
    if (depth > kMaxIncludeDepth) {
        if (too_deep_.empty())
            too_deep_ =
                fmt::format("{}: includes nest deeper than {}: {}\n", chain_.front(), kMaxIncludeDepth, chain_text());
        return nullptr;
    }
    auto found = resolve_(header, includer_name);
    if (!found) return nullptr;
    if (++includes_ > kMaxIncludes || (bytes_ += found->text.size()) > kMaxIncludedBytes) {
        chain_.push_back(found->name);
        const bool count = includes_ > kMaxIncludes;
        too_much_ = fmt::format(
            "{}: more than {}, kdop's limit for one shader (with {}), at {}; files that include others more than "
            "once multiply (25 files that each include the next twice make 2^24 includes): guard each with #ifndef "
            "so that a second include reads nothing\n",
            chain_.front(),
            count ? fmt::format("{} includes", kMaxIncludes)
                  : fmt::format("{} MiB of included text", kMaxIncludedBytes >> 20),
            count ? fmt::format("{} MiB of included text", kMaxIncludedBytes >> 20)
                  : fmt::format("{} includes", kMaxIncludes),
            chain_text());
        return unread();
    }
    auto& kept = sources_.emplace_back(std::make_unique<IncludedSource>(std::move(*found)));
    chain_.push_back(kept->name);
    return new IncludeResult(names_.alias(kept->name), kept->text.data(), kept->text.size(), nullptr);
}

// An include past the limits: no text, under a name no source has.
glslang::TShader::Includer::IncludeResult* GlslangIncluder::unread() {
    return new IncludeResult("kdop-unread-include", "", 0, nullptr);
}

// The chain of includes, up to the first file that includes itself again where there is one.
std::string GlslangIncluder::chain_text() const {
    std::size_t end = chain_.size();
    for (std::size_t j = 1; j < chain_.size() && end == chain_.size(); ++j)
        if (std::find(chain_.begin(), chain_.begin() + j, chain_[j]) != chain_.begin() + j) end = j + 1;
    const std::vector<std::string> shown(chain_.begin(), chain_.begin() + end);
    return fmt::format("{}{}", fmt::join(shown, " -> "),
                       end < chain_.size() ? " -> ... (files that include each other without an include guard)" : "");
}

} // namespace kdop
