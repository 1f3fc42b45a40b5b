// Text from outside kdop (a file's name, a folder's name, a provenance line, the command line) as
// each language kdop writes may hold it without the text becoming code or markup: a shader's file
// name in a C++ string literal, a folder's name in a Markdown table, a provenance line in a
// `//` comment. Each function gives back what the reader of that language sees as the original
// text (or, where the language cannot hold a byte, its \xNN form), never something it would run.
// A name in an HTML page or its links. JSON is nlohmann::json's to escape; a depfile's paths,
// generator/project_shader.h's.
#pragma once

#include <string>
#include <string_view>

namespace kdop {

// A C++ string literal, quotes included, holding exactly `text`: \" \\ \n \t and \? (against
// trigraphs in older standards) by name, every other byte outside printable ASCII in octal (three
// digits, so a following digit is never taken into the escape).
std::string cpp_string_literal(std::string_view text);

// Text for the rest of a `//` line in C++, GLSL, HLSL or WGSL: control bytes and bytes outside
// ASCII as \xNN (a line break would end the comment and start code), and a backslash at the end as
// \x5c (C's and GLSL's preprocessors would join the next line to the comment).
std::string line_comment_text(std::string_view text);

// Text in Markdown prose or a table cell, shown as written: the punctuation that makes markup
// inside a line (\ ` * _ [ ] < > | & ~) backslash-escaped, line breaks and control bytes as \xNN,
// so a name can neither open a link or an HTML tag nor end a table row.
std::string markdown_text(std::string_view text);

// A link or image destination in Markdown, `![alt](here)`: as it is where it holds only letters,
// digits and . _ - /; else in angle brackets, so spaces and parentheses stay part of it, with '<', '>' and '\\'
// backslash-escaped and line breaks and control bytes percent-encoded.
std::string markdown_destination(std::string_view path);

// Inline code in Markdown: `text` between backtick runs one longer than its longest, so a backtick
// inside cannot close it; line breaks and control bytes as \xNN.
std::string markdown_code(std::string_view text);

// Text in HTML, in an element or a quoted attribute, shown as written: & < > " ' as character
// references, control bytes as \xNN.
std::string html_text(std::string_view text);

// A relative URL of a file path: every byte but letters, digits and - . _ ~ / percent-encoded, so
// a name with '#', '?', '%' or a space still names its file.
std::string url_path(std::string_view path);

} // namespace kdop
