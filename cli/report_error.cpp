#include "commands.h"

#include <iostream>

namespace kdop::cli {

int report_error(const std::string& message) {
    std::cerr << message << (message.ends_with('\n') ? "" : "\n");
    return 1;
}

} // namespace kdop::cli
