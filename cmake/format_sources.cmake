# Checks (MODE=check) or applies (MODE=apply) .clang-format on every C++ source of the tree.
# Usage: cmake -DCLANG_FORMAT=<exe> -DROOT=<repo> -DMODE=check|apply -P format_sources.cmake
# The files are listed when it runs, so a new file is checked without reconfiguring.
set(folders core generator runtime reference images sequence harness cli bench stress accuracy fit flip temporal testbed scenes optimize tests examples)
set(sources)
foreach(folder IN LISTS folders)
  file(GLOB_RECURSE found "${ROOT}/${folder}/*.h" "${ROOT}/${folder}/*.cpp")
  list(APPEND sources ${found})
endforeach()
list(SORT sources)
if(MODE STREQUAL "apply")
  execute_process(COMMAND "${CLANG_FORMAT}" -i ${sources} RESULT_VARIABLE failed)
else()
  execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror ${sources} RESULT_VARIABLE failed)
endif()
if(failed)
  message(FATAL_ERROR "clang-format ${MODE} failed (${failed}); `cmake --build build --target format` applies the style")
endif()
