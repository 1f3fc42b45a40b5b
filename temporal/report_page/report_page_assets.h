// report.html's style and script (report.css and viewer.js beside this header), compiled in by
// cmake/embed_text.cmake so that `kdop taa` writes a self-contained page without the source tree.
#pragma once

#include <string_view>

namespace kdop {

std::string_view report_page_style();
std::string_view report_page_script();

} // namespace kdop
