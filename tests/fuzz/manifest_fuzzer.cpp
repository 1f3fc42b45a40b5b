// libFuzzer target: any bytes as a variant manifest, read from a file as every command reads one
// (next to it, forest.axes, so `set: forest.axes` lines resolve). Whatever is refused must be
// refused with a message that names the manifest, holds no raw control bytes and stays short
// (the bytes of a long line are cut); whatever is read must list at least one variant, each once,
// with set files from the manifest's folder only (`set: /etc/passwd` echoed the file's lines), and
// a resolve it records must hold values in their ranges and read back the same once written
// (resolve_lines, what kdop choose writes). Any violation aborts, which libFuzzer reports.
#include "generator/inside_folder.h"
#include "generator/manifest.h"
#include "tests/fuzz/fuzz_checks.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace {

using kdop::fuzz::has_control_bytes;
using kdop::fuzz::require;

// A folder of this process's own with the manifest and the axis file it may name.
const std::filesystem::path& folder() {
    static const std::filesystem::path dir = [] {
        const auto d = std::filesystem::temp_directory_path() / ("kdop-manifest-fuzz-" + std::to_string(getpid()));
        std::filesystem::create_directories(d);
        std::ofstream(d / "forest.axes") << "name: forest\nprovenance: the fuzzer\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n";
        return d;
    }();
    return dir;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::filesystem::path path = folder() / "fuzz.manifest";
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), size);
    auto manifest = kdop::read_manifest(path);
    if (!manifest) {
        const std::string& message = manifest.error().message;
        require(message.rfind(path.string(), 0) == 0, "an error that does not name the manifest", message);
        require(!has_control_bytes(message, false), "an error that echoes control bytes", message);
        require(message.size() < 2000, "an error that repeats a long line whole", message);
        return 0;
    }
    require(!manifest->variants.empty(), "a manifest read with no variant", "");
    for (const std::filesystem::path& set : manifest->set_files)
        require(kdop::is_inside_folder(set, folder()), "a set file outside the manifest's folder", set.string());
    for (std::size_t i = 0; i < manifest->variants.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            require(!(manifest->variants[i].key() == manifest->variants[j].key()), "a variant read twice",
                    manifest->variants[i].key().name());
    if (const auto& r = manifest->resolve) {
        const std::string lines = kdop::resolve_lines(*r);
        require(r->gamma > 0 && r->gamma <= 100, "a gamma out of its range", lines);
        require(r->current_weight > 0 && r->current_weight <= 1, "a current weight out of its range", lines);
        require(r->color_map == kdop::ColorMapKind::power
                    ? r->color_map_exponent >= 0.01 && r->color_map_exponent <= 100
                    : r->color_map_exponent == 1,
                "a color map exponent out of its range", lines);
        const std::filesystem::path again = folder() / "again.manifest";
        std::ofstream(again, std::ios::binary | std::ios::trunc) << lines << "aabb-clip-n9\n";
        auto reread = kdop::read_manifest(again);
        require(reread && reread->resolve && kdop::resolve_lines(*reread->resolve) == lines &&
                    reread->resolve->gamma == r->gamma && reread->resolve->current_weight == r->current_weight &&
                    reread->resolve->color_map_exponent == r->color_map_exponent,
                "a resolve that does not read back as written", lines);
    }
    return 0;
}
