#include "commands.h"

#include <iostream>

namespace kdop::cli {

int report_error(const std::string& message) {
    std::cerr << message << (message.ends_with('\n') ? "" : "\n");
    return 1;
}

void report_validation_messages(const Context& context) {
    for (const std::string& message : context.validation_messages()) std::cerr << "validation: " << message << "\n";
}

} // namespace kdop::cli
