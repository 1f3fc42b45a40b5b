// Reading and writing images through OpenImageIO, in any format it knows (EXR, HDR, PNG, ...),
// whose codecs are loaded on the first image read or written (images/image_codecs.h).
// kdop's images hold linear RGB. Reading takes RGB from the first three channels, decoded to linear
// as the file says (InputSpace; never clamped), and alpha from the fourth if there is one, as
// stored. Writing is all-or-nothing: the file appears complete or not at all (because some of
// OpenImageIO's writers report success on a full disk, a PNG is encoded in memory and its bytes
// written by kdop, which sees every error, and any other file is read back and compared before it
// is renamed into place); and deterministic: the same image gives the same bytes.
#pragma once

#include "core/result.h"
#include "core/write_files.h"
#include "images/image.h"

#include <glm/vec2.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// How a file's values become linear RGB. `from_file`: float formats (EXR, Radiance HDR, float TIFF)
// hold linear values; integer ones (PNG, JPEG, BMP, TGA, 8- and 16-bit TIFF) are decoded by the
// color space OpenImageIO reads from them (oiio:ColorSpace): "linear" as stored, "GammaCorrectedG"
// by the power G, and sRGB, untagged or anything else by sRGB's transfer function, since that is
// what such files hold unless they say otherwise. `linear` and `srgb` override what any file says
// (the commands' `--input-space`).
enum class InputSpace { from_file, linear, srgb };

// What `--input-space` takes: "file", "linear", "srgb".
std::optional<InputSpace> parse_input_space(std::string_view text);

// The header is checked before any pixel is read or allocated: sides beyond `max_side` (a device's
// maxImageDimension2D; 0 for no limit) and images whose pixels would not fit in memory
// (core/memory_budget.h: what the system, the cgroup and `ulimit -v` leave) are refused, naming the
// file and the memory needed, so a small file claiming an enormous image is an error, not an
// allocation failure.
//
// `name`, where given, is the file's own name and `path` the /proc/self/fd path of a descriptor
// already open on it (sequence frames, opened so that no link is followed after the check, see
// sequence/sequence.h): errors name `name`, and its extension picks the format.
Result<Image> read_image(const std::string& path, std::uint32_t max_side = 0, InputSpace space = InputSpace::from_file,
                         const std::string& name = {});

// read_image of the image's top-left corner alone, at most `width` x `height` pixels (all of a
// smaller image): what a caller that tiles or crops the image to that size uses of it. From a file
// decoded a row at a time (a PNG that is not interlaced, a scanline EXR), the rows below the corner
// are never decoded and the columns beyond it never kept, so a 20000x20000 PNG cropped to 320x180
// costs a strip of its rows, not 6 GiB; from any other, it is read whole (and its memory checked
// so), then cropped.
Result<Image> read_image_corner(const std::string& path, std::uint32_t width, std::uint32_t height,
                                InputSpace space = InputSpace::from_file);

// The width and height in `path`'s header, no pixel read: what a caller planning the reads of many
// frames (kdop optimize's sample shares) needs before it reads any of them. `name` as for read_image.
Result<glm::uvec2> read_image_size(const std::string& path, const std::string& name = {});

// An image of data, not color (motion vectors, depth): its values as stored, never decoded, from a
// file with at least `channels` channels (1 to 4); the channels it lacks are 0 (alpha 1). `name`
// as for read_image.
Result<Image> read_data_image(const std::string& path, int channels, const std::string& name = {});

// read_image, refusing an image with a NaN or infinite R, G or B: the error names the file, the
// first such pixel and its value, then `why` (what needs finite colors, and where to look instead).
Result<Image> read_finite_image(const std::string& path, std::string_view why,
                                InputSpace space = InputSpace::from_file);

// The format follows the extension. EXR and TIFF keep 32-bit floats; Radiance HDR keeps RGB with
// about 8 bits relative to each pixel's brightest channel; integer formats such as PNG keep values
// from 0 to 1, and an image with any other value (HDR, negative, NaN) is refused rather than
// clamped, so use EXR for data. Integer formats are written sRGB-encoded and tagged so (PNG's sRGB
// chunk), as every viewer expects, and read back to the same linear values within their precision;
// float formats hold the linear values as they are.
// Lossy formats (JPEG, WebP, HEIF, GIF) are refused: they would not
// give back what was written.
Result<void> write_image(const std::string& path, const Image& image);

// Whether some image format is written for `path`'s extension: a usage error naming `path` where
// none is (for a command to refuse its output's name before it works).
Result<void> check_image_writable(const std::string& path);

// Several images as a set, all or nothing: each is written under a temporary name next to its
// destination, and all are renamed into place only when every one was written.
struct ImageFile {
    std::filesystem::path path;
    const Image* image;
};
Result<void> write_images(const std::vector<ImageFile>& files);

// The writer of one image at `path` (write_image's part of write_atomically), for an output set
// that holds images beside other files. It keeps the image alive until it has written it.
OutputWriter image_writer(std::filesystem::path path, std::shared_ptr<const Image> image);

// What an OutputWriter whose image is made only when the set is written (a sequence's frames)
// does with its temporary: writes `image` to `temporary` and checks it as write_image does, errors
// naming `path`, the file's final name.
//
// `precision` half stores EXR's channels as 16-bit floats (what Arm's NSS captures hold,
// R16G16B16A16_SFLOAT): the values are rounded to the nearest half, and the file read back must
// hold exactly that rounding; a finite value beyond half's range (65504) is refused, naming the
// pixel, rather than written as infinity; any format but EXR is refused.
enum class FloatPrecision { full, half };
Result<void> write_image_to(const std::filesystem::path& temporary, const std::string& path, const Image& image,
                            FloatPrecision precision = FloatPrecision::full);
// write_image_to for an image of data (what read_data_image reads): the first channels.size()
// channels of each pixel, named `channels` ({"R", "G"} for motion, {"Z"} for depth), stored as
// floats in EXR or TIFF (any other format is refused): no channel the data does not use.
Result<void> write_data_image_to(const std::filesystem::path& temporary, const std::string& path, const Image& image,
                                 std::span<const char* const> channels,
                                 FloatPrecision precision = FloatPrecision::full);

} // namespace kdop
