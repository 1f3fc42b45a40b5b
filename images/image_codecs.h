// What kdop asks of OpenImageIO, as one table of functions that lives in a module of its own
// (kdop_image_codecs.so), loaded the first time an image is read, written or drawn on.
//
// Why a module: Debian's OpenImageIO brings about 260 shared libraries (its codecs' chain: OpenCV,
// FFmpeg, LibRaw, DCMTK, ...), and linking them into kdop cost every command 0.16 s of start-up
// before main, most of it the dynamic loader's symbol lookups, including the commands that touch
// no image (`kdop --version`, `kdop list`, `kdop gen`). Loaded on first use, they cost only the
// commands that need them, once. The module links nothing of kdop's but the stateless memory
// budget: what holds state (the inputs noted, the temporaries an interrupt removes, see
// core/input_files.h and core/write_files.h) stays in the executable, which does the checks before a
// file is opened and the all-or-nothing renames after it is written (images/image_read.cpp,
// images/image_write.cpp).
//
// The module is found beside the executable (the build tree's bin/) or, installed, in
// <libdir>/kdop, as the executable's own folder gives them; it must come from the same build, and
// is refused, naming both, if it does not.
#pragma once

#include "core/result.h"
#include "images/image.h"
#include "images/image_io.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace kdop {

// One read (images/image_io.h, read_image and its kin): `file` is opened; messages name `name`
// where given, with its extension picking the format.
struct ImageRead {
    std::uint32_t max_side = 0; // a device's maxImageDimension2D, 0 for no limit
    InputSpace space = InputSpace::from_file;
    int needed = 3;          // the channels needed: RGB (3) or a count of data channels (linear)
    std::string name;        // the file's own name, where `file` is a /proc/self/fd path
    glm::uvec2 corner{0, 0}; // the top-left corner alone, at most this size; 0x0 for the whole image
};

// A line of text drawn white over an image, with the left end of its baseline at (x, y), `size`
// pixels high, or where `max_width` > 0 the largest size from `size` down to 8 at which it fits
// in `max_width` pixels. DejaVu Sans (fonts-dejavu-core), or OpenImageIO's own font without it.
struct TextLine {
    int x = 0, y = 0;
    std::string text;
    int size = 12, max_width = 0;
};

struct ImageCodecs {
    // The image in `file` (checked, decoded to linear and cropped as `read` says), every error
    // naming the file.
    Result<Image> (*read)(const std::string& file, const ImageRead& read);
    // The width and height in `file`'s header; messages name `name` where given.
    Result<glm::uvec2> (*read_size)(const std::string& file, const std::string& name);
    // `image` written to `temporary` in the format its extension names and read back to check it
    // (images/image_io.h, write_image_to); with `data_channels`, as data in a float format.
    // Messages name `path`, the file's final name.
    Result<void> (*write)(const std::filesystem::path& temporary, const std::string& path, const Image& image,
                          std::span<const char* const> data_channels, FloatPrecision precision);
    // Whether some writer takes `path`'s extension; the error says that none does.
    Result<void> (*check_writable)(const std::string& path);
    // `lines` drawn in order over the RGB of `image`.
    Result<void> (*draw_text)(Image& image, std::span<const TextLine> lines);
};

// The codecs, loaded on the first call (from any thread); an error naming the module's path and
// the loader's reason where it cannot be loaded, on this and every later call.
Result<const ImageCodecs*> image_codecs();

// `lines` drawn over `image` by the codecs' draw_text.
Result<void> draw_text(Image& image, std::span<const TextLine> lines);

// The module's one entry point (extern "C", named kImageCodecsEntry): its table, or null where
// `build`, the caller's image_codecs_build(), is not its own: a module of another version, or
// built against another table, would be called with the wrong arguments.
inline constexpr const char* kImageCodecsEntry = "kdop_image_codecs";
using ImageCodecsEntry = const ImageCodecs* (*)(const char* build);
// Raised whenever ImageCodecs changes.
inline constexpr int kImageCodecsRevision = 1;
inline std::string image_codecs_build() {
    return std::string(KDOP_VERSION) + ", table " + std::to_string(kImageCodecsRevision) + " of " +
           std::to_string(sizeof(ImageCodecs)) + " bytes";
}

} // namespace kdop
