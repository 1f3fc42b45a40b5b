#include "generator/source_names.h"

#include <fmt/format.h>

namespace kdop {

bool is_plain_source_name(std::string_view name) {
    if (name.empty()) return false;
    for (char ch : name) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c >= 0x7f || ch == '"' || ch == '\\' || ch == ':' || ch == '%') return false;
    }
    return true;
}

const std::string& SourceNames::alias(const std::string& real) {
    if (auto known = alias_of_.find(real); known != alias_of_.end()) return known->second;
    std::string alias = real;
    // A plain name that an earlier source already took as its alias gets one of its own too.
    while (!is_plain_source_name(alias) || real_of_.count(alias)) alias = fmt::format("kdop-source-{}", next_++);
    real_of_.emplace(alias, real);
    return alias_of_.emplace(real, alias).first->second;
}

std::string SourceNames::real(std::string_view alias) const {
    auto found = real_of_.find(alias);
    return found == real_of_.end() ? std::string(alias) : found->second;
}

} // namespace kdop
