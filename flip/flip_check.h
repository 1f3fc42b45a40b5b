// What kdop flip's options say of themselves before any image is read: the options that do not
// go together, in the run's own terms. Pure (no file is looked at); the command line words each
// conflict with the flags it took them from (cli/flip_command.cpp), and checks the files named
// (core/write_files.h, core/input_files.h) before the run.
#pragma once

#include "flip/flip_run.h"

#include <array>
#include <optional>
#include <string>

namespace kdop {

// The files a run writes (FlipRunOptions' out, exposure_map, csv, histogram), in that order.
enum class FlipOutput { out, exposure_map, csv, histogram };
inline constexpr std::array<FlipOutput, 4> kFlipOutputs{FlipOutput::out, FlipOutput::exposure_map, FlipOutput::csv,
                                                        FlipOutput::histogram};

// The path `options` gives `output`; empty: not written.
const std::string& output_path(const FlipRunOptions& options, FlipOutput output);

struct FlipConflict {
    enum class Kind {
        pixels_per_degree,     // ppd outside check_pixels_per_degree's range
        no_tests,              // no test image to compare with the reference
        maps_of_several_tests, // out or exposure_map, which hold one test's map, and several tests
        map_format,            // `output` (out or exposure_map) is neither .exr nor .png
        histogram_format,      // `output` (histogram) is not a .png
        same_output,           // `output` names the same file as `earlier`, an output before it
    };
    Kind kind;
    FlipOutput output = FlipOutput::out;
    FlipOutput earlier = FlipOutput::out;
};

// The first conflict of the options, or none: pixels_per_degree, no_tests, maps_of_several_tests,
// then each output in order, its format and whether an earlier one names the same file.
std::optional<FlipConflict> check(const FlipRunOptions& options);

// A map file's extension, in lowercase: ".exr" or ".png" are written.
std::string lowercase_extension(const std::string& path);

} // namespace kdop
