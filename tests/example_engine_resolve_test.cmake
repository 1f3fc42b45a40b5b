cmake_minimum_required(VERSION 3.25)
# Builds examples/engine_resolve against an installation of this kdop build, as an engine project
# would, and runs it on lavapipe: a uniform-buffer compute resolve and a vertex + fragment resolve,
# both created and run through kdop/vulkan_pipeline.h with VK_NO_PROTOTYPES and a function table,
# written in GLSL and again in HLSL; the example itself fails on a validation message or when any of
# the four resolves disagrees with the GLSL compute one.
# Inputs: SOURCE, BUILD, GENERATOR, INSTALL_FROM (the kdop build directory).

include(${CMAKE_CURRENT_LIST_DIR}/project_test_support.cmake)

file(REMOVE_RECURSE ${BUILD})
file(COPY ${SOURCE}/ DESTINATION ${BUILD}/src)
run_checked(out ${CMAKE_COMMAND} --install ${INSTALL_FROM} --prefix ${BUILD}/prefix)
run_checked(out ${CMAKE_COMMAND} -S ${BUILD}/src -B ${BUILD}/build -G ${GENERATOR} -DCMAKE_PREFIX_PATH=${BUILD}/prefix)
run_checked(out ${CMAKE_COMMAND} --build ${BUILD}/build)

# Nothing of the loader is linked: the example opens it itself.
file(READ ${BUILD}/build/build.ninja ninja)
if(ninja MATCHES "libvulkan\\.so")
  message(FATAL_ERROR "engine_resolve links the Vulkan loader; with VK_NO_PROTOTYPES it must not need it")
endif()

run_checked(out ${BUILD}/build/engine_resolve llvmpipe)
foreach(expected IN ITEMS "resolve_compute: compute shader, 6 binding" "resolve_fragment: fragment shader, 2 binding"
                          "fullscreen: vertex shader, 0 binding"
                          "set 0 binding 1: nearest_sampler \\(sampler\\)"
                          "set 0 binding 3: resolved_frame \\(storage image, VkFormat 109\\)"
                          "set 1 binding 0: parameters \\(uniform buffer, 12 bytes\\)"
                          "set 1 binding 1: clip_distances \\(storage buffer\\)"
                          "set 0 binding 0: frames \\(combined image sampler x2\\)" "push constants: 4 bytes"
                          "hlsl_resolve_compute: compute shader, 7 binding" "hlsl_resolve_fragment: fragment shader, 3 binding"
                          "hlsl_fullscreen: vertex shader, 0 binding"
                          "set 0 binding 4: history_sampler \\(sampler\\)" "set 0 binding 2: frame_samplers \\(sampler x2\\)"
                          "set 0 binding 0: frames \\(sampled image x2\\)"
                          "dynamic rendering pipeline created" "both GLSL resolves ran on llvmpipe"
                          "both HLSL resolves ran on llvmpipe"
                          "GLSL compute and fragment resolves agree" "HLSL compute and fragment resolves agree"
                          "upscale_compute: compute shader, 4 binding" "hlsl_upscale_compute: compute shader, 4 binding"
                          "push constants: 12 bytes" "GLSL and HLSL TAAU resolves \\([0-9x to,]+ frames\\) agree"
                          "validation layer on, 0 message\\(s\\)")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "engine_resolve did not print '${expected}':\n${out}")
  endif()
endforeach()
# The ghost in the history is clipped away: the clip moves some pixels' history far.
if(NOT out MATCHES "HLSL: history moved by the clip: mean [0-9.]+, largest 0\\.[3-9]|HLSL: history moved by the clip: mean [0-9.]+, largest 1\\.")
  message(FATAL_ERROR "engine_resolve's HLSL clip did not take the ghost out:\n${out}")
endif()
if(NOT out MATCHES "history moved by the clip: mean [0-9.]+, largest 0\\.[3-9]|largest 1\\.")
  message(FATAL_ERROR "engine_resolve's clip did not take the ghost out:\n${out}")
endif()
message(STATUS "ok: ran on lavapipe:\n${out}")
