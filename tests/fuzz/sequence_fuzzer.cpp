// libFuzzer target: any bytes as a frame sequence's sequence.json, in a folder that holds two small
// frames (color/0000.exr, motion/0000.exr) for the sequence to name. Whatever is refused must be
// refused with a message that names sequence.json, holds no raw control bytes and stays short;
// whatever is read must have a size within the format's limits, a color file for every frame and
// motion for every frame with a history, and its frames must load or be refused the same way.
// Any violation aborts, which libFuzzer reports.
#include "images/image_io.h"
#include "sequence/sequence.h"
#include "tests/fuzz/fuzz_checks.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace {

using kdop::fuzz::require;

const std::filesystem::path& folder() {
    static const std::filesystem::path dir = [] {
        const auto d = std::filesystem::temp_directory_path() / ("kdop-sequence-fuzz-" + std::to_string(getpid()));
        std::filesystem::create_directories(d / "color");
        std::filesystem::create_directories(d / "motion");
        const kdop::Image frame(4, 2, {0.25f, 0.5f, 0.75f, 1.0f});
        require(bool(kdop::write_image((d / "color/0000.exr").string(), frame)), "cannot write the frame", "");
        require(bool(kdop::write_image((d / "motion/0000.exr").string(), frame)), "cannot write the motion", "");
        return d;
    }();
    return dir;
}

void require_message(const std::string& message) {
    kdop::fuzz::require_refusal_message(message, "sequence.json", folder().string());
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path dir = folder();
    std::ofstream(dir / "sequence.json", std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    auto sequence = kdop::read_sequence(dir);
    if (!sequence) {
        require_message(sequence.error().message);
        return 0;
    }
    require(sequence->width >= 1 && sequence->width <= 16384 && sequence->height >= 1 && sequence->height <= 16384,
            "a size outside the format's limits", "");
    require(!sequence->frames.empty(), "a sequence read with no frame", "");
    for (std::size_t i = 0; i < sequence->frames.size(); ++i) {
        require(!sequence->frames[i].color.empty(), "a frame read with no color", "");
        require(sequence->starts_history(i) || !sequence->frames[i].motion.empty(), "a history without motion", "");
    }
    auto frame = kdop::load_frame(*sequence, 0);
    if (!frame) require_message(frame.error().message);
    return 0;
}
