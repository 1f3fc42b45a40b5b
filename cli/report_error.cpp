#include "cli/commands.h"

#include "core/shown_text.h"
#include "generator/command_line.h"

#include <iostream>
#include <set>

namespace kdop::cli {

int report_error(const std::string& message) {
    std::cerr << "kdop: " << terminal_text(message) << (message.ends_with('\n') ? "" : "\n");
    return 1;
}

int usage_error(const std::string& message) {
    report_error(message);
    return kUsageError;
}

int report(const Error& error) { return error.usage ? usage_error(error.message) : report_error(error.message); }

void report_validation_messages(std::span<const std::string> messages) {
    for (const std::string& message : messages) std::cerr << "validation: " << terminal_text(message) << "\n";
}

void warn_fitted_space(std::span<const VariantSpec> specs, const ColorMap& used, std::string_view clipping) {
    std::set<std::string> warned;
    for (const VariantSpec& spec : specs)
        if (auto warning = fitted_space_mismatch(spec.set, used, clipping);
            warning && warned.insert(spec.set.name).second)
            std::cerr << "warning: " << terminal_text(*warning) << "\n";
}

} // namespace kdop::cli
