// libFuzzer target: any bytes as an axis-set file, with the emitter behind the parser. Whatever
// the parser accepts must emit every mode, neighborhood and form of GLSL in which no text from the
// file leaves a comment (the injection the adversarial run found) and no axis became zero or
// infinite (the loop form's raw axes), and whose provenance is UTF-8, which the registry's JSON must
// hold (a Latin-1 one failed at the end of kdop gen). Everything it refuses must be refused with a message that
// names the file and holds no raw control bytes. Any violation aborts, which libFuzzer reports.
#include "core/utf8.h"
#include "generator/axis_set.h"
#include "generator/clip_emitter.h"
#include "generator/variant_spec.h"
#include "tests/fuzz/fuzz_checks.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>
#include <string_view>

namespace {

using kdop::fuzz::has_control_bytes;
using kdop::fuzz::require;

// Whether `word` stands in `code` as a token of its own ("inf", not the "inf" of a set named "tinf").
bool has_token(std::string_view code, std::string_view word) {
    const auto identifier = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (std::size_t at = code.find(word); at != std::string_view::npos; at = code.find(word, at + 1)) {
        const bool starts = at == 0 || !identifier(code[at - 1]);
        const bool ends = at + word.size() == code.size() || !identifier(code[at + word.size()]);
        if (starts && ends) return true;
    }
    return false;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto set = kdop::parse_axis_set(text, "fuzz.axes");
    if (!set) {
        const std::string& message = set.error().message;
        require(message.rfind("fuzz.axes", 0) == 0, "an error that does not name the file", message);
        require(!has_control_bytes(message, false), "an error that echoes control bytes", message);
        return 0;
    }
    require(!kdop::first_non_utf8_byte(set->provenance), "a provenance that is not UTF-8", set->provenance);
    for (kdop::Mode mode : kdop::kAllModes)
        for (kdop::Neighborhood n : kdop::kAllNeighborhoods)
            for (kdop::Form form : {kdop::Form::unrolled, kdop::Form::loop}) {
                const std::string glsl = kdop::emit_function({*set, mode, n, form});
                // Text from the file stands only in comments, so with no control byte in the output
                // (a line break ends a `//` comment) none of it can become code.
                require(!has_control_bytes(glsl, true), "generated code with a control byte", glsl);
                for (std::size_t start = 0; start < glsl.size();) {
                    const std::size_t end = std::min(glsl.find('\n', start), glsl.size());
                    const std::string_view line = std::string_view(glsl).substr(start, end - start);
                    const std::string_view code = line.substr(0, line.find("//"));
                    require(!has_token(code, "inf") && !has_token(code, "nan") && !has_token(code, "-nan"),
                            "a non-finite literal in generated code", glsl);
                    require(code.find("vec3(0.0, 0.0, 0.0)") == std::string_view::npos, "an axis that became zero",
                            glsl);
                    start = end + 1;
                }
            }
    return 0;
}
