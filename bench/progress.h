// Progress of a long bench step on stderr: "[ 12/51] timing dop32-clip-n9". On a terminal the line
// is rewritten in place; otherwise (a log, CI) each step is one line so nothing is lost.
#pragma once

#include <cstddef>
#include <string>

namespace kdop::bench {

class Progress {
public:
    Progress(std::string step, std::size_t total);
    ~Progress(); // ends the line
    void advance(const std::string& item);

private:
    std::string step_;
    std::size_t total_, done_ = 0;
    bool terminal_;
};

} // namespace kdop::bench
