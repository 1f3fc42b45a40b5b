cmake_minimum_required(VERSION 3.25)
# kdop_add_variants() refuses at configure time what kdop-gen would refuse at every build, or what
# would make every build regenerate: a NAMESPACE that is a C++ keyword, a HEADER that is also the
# registry's source, a shader path holding '$', '#' or a quote (CMake's depfile for Ninja cannot
# carry them), an HLSL_ENTRY that is no function name. Each case configures a one-target project
# against kdop's build tree.
# Inputs: BUILD (a scratch folder), kdop_DIR (kdop's build tree), GENERATOR.

function(expect_refused name arguments message)
  set(dir "${BUILD}/${name}")
  file(REMOVE_RECURSE "${dir}")
  file(MAKE_DIRECTORY "${dir}/src")
  file(WRITE "${dir}/src/CMakeLists.txt"
       "cmake_minimum_required(VERSION 3.25)\nproject(refusal LANGUAGES NONE)\nfind_package(kdop CONFIG REQUIRED)\n"
       "add_custom_target(app)\nkdop_add_variants(app SETS aabb ${arguments})\n")
  execute_process(COMMAND ${CMAKE_COMMAND} -S "${dir}/src" -B "${dir}/build" -G "${GENERATOR}" "-Dkdop_DIR=${kdop_DIR}"
                  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REPLACE "\n  " " " err "${err}") # CMake wraps its messages
  string(FIND "${err}" "${message}" found)
  if(result EQUAL 0 OR found EQUAL -1)
    message(FATAL_ERROR "${name}: expected a refusal saying '${message}'; configure exited ${result}:\n${out}\n${err}")
  endif()
  message(STATUS "ok: ${name}")
endfunction()

expect_refused(keyword "NAMESPACE int" "NAMESPACE int holds the C++ keyword 'int'")
expect_refused(nested_keyword "NAMESPACE app::class" "holds the C++ keyword 'class'")
expect_refused(reserved "NAMESPACE __app" "a name reserved for the C++ implementation")
expect_refused(header_is_source "HEADER app_hdr.cpp" "HEADER app_hdr.cpp is also the registry's source")
expect_refused(quoted_header "HEADER [=[a\"b.h]=]" "must be a file name that #include")
expect_refused(dollar "SHADERS [=[shaders/a$b.comp]=]" "holds '$', '#', a quote or a line break")
expect_refused(hash "SHADERS [=[shaders/a#b.comp]=]" "holds '$', '#', a quote or a line break")
expect_refused(quote "SHADERS [=[shaders/x\" ? (__builtin_puts(\"INJECTED\"), \"y\") : \".comp]=]"
               "holds '$', '#', a quote or a line break")
expect_refused(hlsl_entry "SHADERS shaders/a.cs.hlsl HLSL_ENTRY [=[main()]=]" "is not an HLSL function name")
expect_refused(hlsl_entry_spaces "SHADERS shaders/a.cs.hlsl HLSL_ENTRY [=[CS Main]=]" "is not an HLSL function name")
