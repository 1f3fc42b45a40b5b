#include "fit/fitted_set.h"

#include "core/utf8.h"

#include <fmt/format.h>

namespace kdop {

Result<std::string> fitted_set_file(const FittedSetText& text, std::span<const glm::dvec3> axes) {
    std::string out;
    // The comments and the provenance name the inputs, whose paths may hold any byte; an axis file
    // is UTF-8 lines (axis_set.h), so a line break or a Latin-1 name is written as \xNN.
    for (const std::string& line : text.comments) out += line.empty() ? "#\n" : "# " + utf8_line(line) + "\n";
    out += fmt::format("name: {}\nprovenance: {}\n", text.name, utf8_line(text.provenance));
    if (text.color_map) out += fmt::format("color_map: {}\n", to_string(*text.color_map));
    // Nine decimals: the fitted directions to about 1e-9 rad, far below what moves the volume.
    for (const glm::dvec3& a : axes) out += fmt::format("vec3({:.9f}, {:.9f}, {:.9f}),\n", a.x, a.y, a.z);
    if (auto parsed = parse_axis_set(out, text.name + ".axes"); !parsed)
        return fail(fmt::format("the fitted set cannot be written as an axis file: {}", parsed.error().message));
    return out;
}

} // namespace kdop
