// Loading the image codecs' module (images/image_codecs.h) on first use.
#include "images/image_codecs.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <filesystem>
#include <system_error>

namespace kdop {
namespace {

constexpr const char* kModuleName = "kdop_image_codecs.so";

Result<const ImageCodecs*> load() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path folder = fs::read_symlink("/proc/self/exe", ec).parent_path();
    if (ec) return fail(fmt::format("cannot find kdop's image codecs: /proc/self/exe: {}", ec.message()));
    // Beside the executable in the build tree; in <libdir>/kdop where kdop is installed, found
    // from the executable's folder so that an installation may move.
    const fs::path candidates[] = {folder / kModuleName, folder / KDOP_CODECS_INSTALLED_DIR / kModuleName};
    for (const fs::path& module : candidates) {
        if (!fs::exists(module, ec)) continue;
        // Never closed: OpenImageIO's threads and exit handlers run from it until the process ends.
        void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) return fail(fmt::format("cannot load kdop's image codecs: {}", dlerror()));
        const auto entry = reinterpret_cast<ImageCodecsEntry>(dlsym(handle, kImageCodecsEntry));
        if (!entry) return fail(fmt::format("{}: not kdop's image codecs (no {})", module.string(), kImageCodecsEntry));
        const std::string build = image_codecs_build();
        if (const ImageCodecs* codecs = entry(build.c_str())) return codecs;
        return fail(fmt::format("{}: image codecs of another kdop build than this one ({}); reinstall kdop",
                                module.string(), build));
    }
    return fail(fmt::format("cannot read or write images: kdop's image codecs are missing: neither {} nor {} "
                            "exists; reinstall kdop",
                            candidates[0].string(), candidates[1].lexically_normal().string()));
}

} // namespace

Result<const ImageCodecs*> image_codecs() {
    static const Result<const ImageCodecs*> loaded = load();
    return loaded;
}

Result<void> draw_text(Image& image, std::span<const TextLine> lines) {
    auto codecs = image_codecs();
    if (!codecs) return std::unexpected(codecs.error());
    return (*codecs)->draw_text(image, lines);
}

} // namespace kdop
