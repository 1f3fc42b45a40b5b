// libFuzzer target: any bytes as an NSS capture's 0000.json (sequence/nss_capture.h), in a folder
// that holds one small frame of each stream at ratio 2 (8x4 ground truth, 4x2 color, depth and
// motion). Whatever is refused must be refused with a message that names the JSON or a file of the
// capture, holds no raw control bytes and stays short; whatever is read must have sizes the ratio
// allows, at least one frame, finite jitter within half an input pixel and a positive finite
// exposure, and its first frame must load or be refused the same way. Any violation aborts, which
// libFuzzer reports.
#include "images/image_io.h"
#include "sequence/nss_capture.h"
#include "tests/fuzz/fuzz_checks.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace {

using kdop::fuzz::require;

const std::filesystem::path& folder() {
    static const std::filesystem::path dir = [] {
        const auto d = std::filesystem::temp_directory_path() / ("kdop-nss-fuzz-" + std::to_string(getpid()));
        const kdop::Image input(4, 2, {0.25f, 0.5f, 0.75f, 1.0f}), truth(8, 4, {0.5f, 0.25f, 0.125f, 1.0f});
        for (const char* stream : {"color", "depth", "motion"}) {
            std::filesystem::create_directories(d / "x2" / stream / "0000");
            require(bool(kdop::write_image((d / "x2" / stream / "0000" / "0000.exr").string(), input)),
                    "cannot write a frame", stream);
        }
        std::filesystem::create_directories(d / "ground_truth" / "0000");
        require(bool(kdop::write_image((d / "ground_truth" / "0000" / "0000.exr").string(), truth)),
                "cannot write the ground truth", "");
        return d;
    }();
    return dir;
}

void require_message(const std::string& message) {
    kdop::fuzz::require_refusal_message(message, "0000.json", folder().string());
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path dir = folder();
    std::ofstream(dir / "0000.json", std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    auto capture = kdop::read_nss_capture(dir, "0000", 2.0);
    if (!capture) {
        require_message(capture.error().message);
        return 0;
    }
    require(capture->width == 8 && capture->height == 4, "a target size the ground truth does not have", "");
    require(capture->input_width == 4 && capture->input_height == 2, "an input size the files do not have", "");
    require(capture->frames.size() == 1, "a frame count the files do not have", "");
    for (const kdop::NssFrame& f : capture->frames) {
        require(std::isfinite(f.jitter.x) && std::isfinite(f.jitter.y), "a non-finite jitter read", "");
        require(std::abs(f.jitter.x) <= 0.5001f && std::abs(f.jitter.y) <= 0.5001f, "a jitter beyond half a pixel", "");
        require(f.exposure > 0 && std::isfinite(f.exposure), "an exposure that is no multiplier", "");
    }
    const kdop::NssFrames frames(*capture);
    auto frame = frames.frame(0);
    if (!frame) require_message(frame.error().message);
    return 0;
}
