cmake_minimum_required(VERSION 3.25) # policies: if() reads TRUE and FALSE as booleans
# Builds examples/taa_resolve against this kdop build tree, as a renderer project would, and runs it
# on lavapipe: its TAA resolve includes the dop22 clip at build time, and the one-call helper makes
# a pipeline of it. Then checks the build's dependencies on the shader: a comment added to it
# regenerates, but the SPIR-V is the same, so nothing recompiles.
# Inputs: SOURCE, BUILD, GENERATOR, kdop_DIR.

include(${CMAKE_CURRENT_LIST_DIR}/project_test_support.cmake)

file(REMOVE_RECURSE ${BUILD})
file(COPY ${SOURCE}/ DESTINATION ${BUILD}/src)
run_checked(out ${CMAKE_COMMAND} -S ${BUILD}/src -B ${BUILD}/build -G ${GENERATOR} -Dkdop_DIR=${kdop_DIR})
run_checked(out ${CMAKE_COMMAND} --build ${BUILD}/build)

run_checked(out ${BUILD}/build/taa_resolve llvmpipe)
foreach(expected IN ITEMS "taa_resolve: pipeline created on llvmpipe" "set 0 binding 0: current_frame"
                          "set 0 binding 2: rectified_history \\(storage image\\)" "push constant current_weight: 4 bytes at 8")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "taa_resolve did not print '${expected}':\n${out}")
  endif()
endforeach()
message(STATUS "ok: ran on lavapipe:\n${out}")

set(function ${BUILD}/build/kdop_variants/taa_resolve/functions/dop22-clip-n9.glsl)
file(READ ${function} text)
if(NOT text MATCHES "vec3 kdop_dop22_clip_n9\\(vec3 current, vec3 history, vec3 neighborhood\\[9\\]\\)")
  message(FATAL_ERROR "FUNCTIONS did not write the includable function to ${function}")
endif()
string(REPLACE ".glsl" ".hlsl" function "${function}")
file(READ ${function} text)
if(NOT text MATCHES "float3 kdop_dop22_clip_n9\\(float3 current, float3 history, float3 neighborhood\\[9\\]\\)")
  message(FATAL_ERROR "FUNCTIONS did not write the HLSL function to ${function}")
endif()
string(REPLACE ".hlsl" ".wgsl" function "${function}")
file(READ ${function} text)
if(NOT text MATCHES "fn kdop_dop22_clip_n9\\(current: vec3f, history: vec3f, neighborhood: array<vec3f, 9>\\) -> vec3f")
  message(FATAL_ERROR "FUNCTIONS did not write the WGSL function to ${function}")
endif()

run_checked(out ${CMAKE_COMMAND} --build ${BUILD}/build)
if(out MATCHES "kdop: generating|Building CXX")
  message(FATAL_ERROR "no-op rebuild did work:\n${out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1) # past the time-stamp resolution
file(APPEND ${BUILD}/src/taa_resolve.comp "// a comment changes no instruction\n")
run_checked(out ${CMAKE_COMMAND} --build ${BUILD}/build)
if(NOT out MATCHES "kdop: generating" OR out MATCHES "Building CXX")
  message(FATAL_ERROR "after a comment in the shader: expected regeneration and no compilation:\n${out}")
endif()
message(STATUS "ok: the shader is a dependency; unchanged SPIR-V recompiles nothing")
