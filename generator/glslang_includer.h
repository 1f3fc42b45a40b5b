// glslang's side of an IncludeResolver (glsl_compiler.h): each #include looked up through it, with
// the limits glslang itself does not set. Without them, files that include each other without a
// guard recursed until memory ran out, and an include bomb (25 files, each including the next
// twice: 2^24 includes) ran kdop-gen past a minute and a gigabyte, growing.
#pragma once

#include "generator/glsl_compiler.h"
#include "generator/source_names.h"

#include <glslang/Public/ShaderLang.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace kdop {

// How deeply includes may nest.
inline constexpr std::size_t kMaxIncludeDepth = 32;
// How many includes one shader may make, and how much text they may bring in all together. A
// shader library's headers, each guarded and included from many places, come to hundreds of
// includes and a few megabytes of text; the bomb reaches the count in 0.4 s and 47 MB.
inline constexpr std::size_t kMaxIncludes = 10000;
inline constexpr std::size_t kMaxIncludedBytes = std::size_t(16) << 20;

// Included texts live as long as this object, which must outlive the compilation. glslang knows
// every source by its name in `names`.
class GlslangIncluder : public glslang::TShader::Includer {
public:
    GlslangIncluder(const IncludeResolver& resolve, SourceNames& names) : resolve_(resolve), names_(names) {}
    IncludeResult* includeLocal(const char* header, const char* includer, size_t depth) override;
    IncludeResult* includeSystem(const char* header, const char* includer, size_t depth) override {
        return includeLocal(header, includer, depth);
    }
    void releaseInclude(IncludeResult* result) override { delete result; }

    // Why includes nested too deeply, or empty. glslang's own errors follow it.
    const std::string& too_deep() const { return too_deep_; }
    // Why the includes came to too much, or empty. Everything after is unread, so glslang's own
    // errors say nothing of the shader.
    const std::string& too_much() const { return too_much_; }

private:
    IncludeResult* unread();
    std::string chain_text() const;

    const IncludeResolver& resolve_;
    SourceNames& names_;
    std::vector<std::unique_ptr<IncludedSource>> sources_;
    std::vector<std::string> chain_; // the real names of the files above the include at hand
    std::string too_deep_, too_much_;
    std::size_t includes_ = 0, bytes_ = 0;
};

} // namespace kdop
