#include "commands.h"

#include "command_line.h"

#include <iostream>

namespace kdop::cli {

int report_error(const std::string& message) {
    std::cerr << "kdop: " << message << (message.ends_with('\n') ? "" : "\n");
    return 1;
}

int usage_error(const std::string& message) {
    report_error(message);
    return kUsageError;
}

void report_validation_messages(const Context& context) {
    for (const std::string& message : context.validation_messages()) std::cerr << "validation: " << message << "\n";
}

} // namespace kdop::cli
