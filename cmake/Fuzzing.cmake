# Instrumentation for the libFuzzer targets (`-DKDOP_FUZZ=ON`, see .ci/sanitizers.sh): every kdop
# library is compiled with coverage for libFuzzer and with the address and undefined-behavior
# sanitizers, so a fuzzer finds what goes wrong anywhere in kdop's code behind its entry point.
# Third-party libraries (OpenImageIO, glslang) run uninstrumented, as Debian ships them.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "KDOP_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++-16")
endif()
# Debian's glslang is built without RTTI, so the vptr check cannot run.
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr -fno-omit-frame-pointer)
add_link_options(-fsanitize=address,undefined)
# libstdc++ 12 declares std::expected only when the compiler reports C++20 concepts in full
# (__cpp_concepts >= 202002L, for conditionally trivial special members, P0848). Clang 16 implements
# P0848 but still reports 201907L, so it is told the value; the same standard library as every
# Debian package then serves kdop, OpenImageIO and libFuzzer alike.
if(CMAKE_CXX_COMPILER_VERSION VERSION_LESS 19)
  add_compile_options(-U__cpp_concepts -D__cpp_concepts=202002L)
endif()
