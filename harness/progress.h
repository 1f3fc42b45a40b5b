// Progress of a long step on stderr: "[12/51] timing dop32-clip-n9  0:42 elapsed, about 1:13 left",
// with a unit the rate too ("[120/2400] TAA ... grass3d-ghosting (2 of 24)  0:42 elapsed, 2.9
// frames/s, about 13:06 left").
// On a terminal the line is rewritten in place and cleared when the step ends, so it never runs
// into a table printed afterwards; otherwise (a log, CI) a step is one line when its item differs
// from the last line's, and steps of one item (the frames of a sequence) a line each tenth of the
// total, so a log says where the work is without a line per frame.
// The estimate assumes the remaining steps take as long as the finished ones did on average.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace kdop {

class Progress {
public:
    // `unit`: what a step is, for the rate ("frames"); none: no rate.
    Progress(std::string step, std::size_t total, std::string unit = {});
    ~Progress() { finish(); }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // One more item is done (or `steps` more: other ranks' frames, kdop taa under mpirun).
    void advance(const std::string& item, std::size_t steps = 1);
    // Clears the line on a terminal; called by the destructor.
    void finish();

private:
    std::string step_, unit_;
    std::size_t total_, done_ = 0;
    std::string last_item_;      // of the last line written to a log
    std::size_t last_tenth_ = 0; // of the total, at that line
    bool terminal_, finished_ = false;
    std::chrono::steady_clock::time_point start_;
};

// "1:05", "12:30", "1:02:03": a duration for a progress line.
std::string clock_text(double seconds);

} // namespace kdop
