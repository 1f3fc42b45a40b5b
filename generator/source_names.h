// The names glslang knows a compilation's sources by. glslang writes a source's name into the text
// it compiles, unescaped: `#line N "<includer>"` after each #include (and `__FILE__`). A file named
// `e"\n#define mix(a,b,c) (b)\n#line 11 "taa.comp` thus became code, and compiled to a resolve
// without its clip; a plain `q"x.comp` failed as "q:9: error: '#line'". So glslang is given a name it
// carries as it is, the real one where that is plain, and its messages are mapped back.
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace kdop {

// Whether glslang's `#line N "name"` and its messages ("ERROR: name:12: ...") carry `name` as it
// is: printable ASCII without '"', '\\', ':' (which would end the name in a message) or '%'.
bool is_plain_source_name(std::string_view name);

class SourceNames {
public:
    // glslang's name for the source called `real`: `real` itself where it is plain and no other
    // source has it as its name; else "kdop-source-N", which no other source has.
    const std::string& alias(const std::string& real);
    // The real name of the source glslang calls `alias`; `alias` itself where no source has it.
    std::string real(std::string_view alias) const;

private:
    std::map<std::string, std::string> alias_of_;             // by real name
    std::map<std::string, std::string, std::less<>> real_of_; // by alias
    int next_ = 0;
};

} // namespace kdop
