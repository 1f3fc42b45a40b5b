cmake_minimum_required(VERSION 3.25) # policies: if() reads TRUE and FALSE as booleans
# Builds examples/consumer as an outside project would, runs it, and checks kdop_add_variants()'s
# dependencies: nothing regenerates on a no-op rebuild; touching a user axis file regenerates but,
# as nothing changed, recompiles nothing; editing it regenerates and recompiles; a rebuilt kdop-gen
# regenerates.
# Inputs: SOURCE, BUILD, GENERATOR, and how the consumer gets kdop (see examples/consumer):
#   -Dkdop_DIR=<build dir> -DKDOP_GEN=<its kdop-gen>   the build tree (KDOP_GEN is touched)
#   -DINSTALL_FROM=<build dir>                          an installation of it, moved after installing
#   -DKDOP_SUBDIRECTORY=<source dir>                    add_subdirectory, generator only

include(${CMAKE_CURRENT_LIST_DIR}/project_test_support.cmake)

# Builds; GENERATES and COMPILES (TRUE/FALSE) say whether variants must be regenerated and C++ compiled.
function(build_and_expect generates compiles reason)
  run_checked(out ${CMAKE_COMMAND} --build ${BUILD}/build --target consumer)
  foreach(check IN ITEMS "generates;kdop: generating" "compiles;Building CXX object")
    list(GET check 0 what)
    list(GET check 1 text)
    string(FIND "${out}" "${text}" found)
    if(${${what}} AND found EQUAL -1)
      message(FATAL_ERROR "${reason}: expected '${text}', the build said:\n${out}")
    elseif(NOT ${${what}} AND NOT found EQUAL -1)
      message(FATAL_ERROR "${reason}: expected no '${text}', the build said:\n${out}")
    endif()
  endforeach()
  message(STATUS "ok: ${reason}")
endfunction()

# Work on a copy, so touching its axis file does not touch the repository.
file(REMOVE_RECURSE ${BUILD})
file(COPY ${SOURCE}/ DESTINATION ${BUILD}/src)

set(configure_args)
if(INSTALL_FROM)
  # Install, then move the prefix: the package must find everything relative to itself and name
  # neither kdop's source nor its build tree.
  run_checked(out ${CMAKE_COMMAND} --install ${INSTALL_FROM} --prefix ${BUILD}/staged)
  file(RENAME ${BUILD}/staged ${BUILD}/prefix)
  file(GLOB_RECURSE installed_cmake ${BUILD}/prefix/*.cmake)
  get_filename_component(kdop_source "${SOURCE}/../.." ABSOLUTE)
  expect_relocatable("${installed_cmake}" "${kdop_source};${INSTALL_FROM};${BUILD}/staged")
  foreach(part IN ITEMS bin/kdop-gen bin/kdop include/kdop/variant.h share/kdop/axis_sets/dop22.axes
                        share/kdop/functions/dop32-clip-n9.glsl share/kdop/functions/dop32-clip-n9.hlsl
                        share/kdop/functions/dop32-clip-n9.wgsl
                        share/doc/kdop/LICENSE share/doc/kdop/NOTICE)
    if(NOT EXISTS ${BUILD}/prefix/${part})
      message(FATAL_ERROR "cmake --install did not install ${part}")
    endif()
  endforeach()
  # The moved kdop finds its image codecs (images/image_codecs.h) in the installation and writes EXR.
  file(GLOB_RECURSE codecs ${BUILD}/prefix/*/kdop_image_codecs.so)
  if(NOT codecs)
    message(FATAL_ERROR "cmake --install did not install kdop_image_codecs.so")
  endif()
  run_checked(out ${BUILD}/prefix/bin/kdop textures --out ${BUILD}/textures --width 8 --height 8)
  file(GLOB textures ${BUILD}/textures/*.exr)
  if(NOT textures)
    message(FATAL_ERROR "the installed kdop wrote no texture:\n${out}")
  endif()
  list(APPEND configure_args -DCMAKE_PREFIX_PATH=${BUILD}/prefix)
elseif(KDOP_SUBDIRECTORY)
  list(APPEND configure_args -DKDOP_SUBDIRECTORY=${KDOP_SUBDIRECTORY})
else()
  list(APPEND configure_args -Dkdop_DIR=${kdop_DIR})
endif()

run_checked(out ${CMAKE_COMMAND} -S ${BUILD}/src -B ${BUILD}/build -G ${GENERATOR} ${configure_args})
if(KDOP_SUBDIRECTORY)
  # As a subproject, kdop leaves the parent's build type and testing alone and looks for nothing
  # the generator does not need.
  file(STRINGS ${BUILD}/build/CMakeCache.txt entries REGEX "^[A-Za-z_]") # the entries, not their comments
  foreach(unwanted IN ITEMS "CMAKE_BUILD_TYPE:STRING=Release" "OpenImageIO" "Vulkan" "GLPK" "Qhull" "BUILD_TESTING")
    list(FILTER entries EXCLUDE REGEX "^KDOP_") # kdop's own options describe what they leave out
    string(FIND "${entries}" "${unwanted}" found)
    if(NOT found EQUAL -1)
      message(FATAL_ERROR "add_subdirectory(kdop) with KDOP_GENERATOR_ONLY put ${unwanted} in the parent's cache")
    endif()
  endforeach()
  file(READ ${BUILD}/build/build.ninja ninja)
  string(FIND "${ninja}" "kdop_tests" found)
  if(NOT found EQUAL -1)
    message(FATAL_ERROR "add_subdirectory(kdop) builds kdop's tests")
  endif()
endif()
build_and_expect(TRUE TRUE "first build")

run_checked(out ${BUILD}/build/consumer dop22-clip-n9)
if(NOT out MATCHES "found dop22-clip-n9 \\(clip, 11 axes\\): usable")
  message(FATAL_ERROR "consumer did not find dop22-clip-n9:\n${out}")
endif()
# The resolve its manifest records, read from the header's constants (C++17).
if(NOT out MATCHES "resolve: gamma 1, current weight 0.1, bilinear history")
  message(FATAL_ERROR "consumer did not print the manifest's resolve:\n${out}")
endif()
run_checked(out ${BUILD}/build/consumer my-scene-clip-n9)
if(NOT out MATCHES "found my-scene-clip-n9 \\(clip, 7 axes\\): usable")
  message(FATAL_ERROR "consumer did not find my-scene-clip-n9:\n${out}")
endif()
execute_process(COMMAND ${BUILD}/build/consumer dop32-clip-n9 RESULT_VARIABLE result OUTPUT_QUIET ERROR_QUIET)
if(result EQUAL 0)
  message(FATAL_ERROR "consumer claims a variant it was not built with")
endif()

build_and_expect(FALSE FALSE "no-op rebuild")
touch_later(${BUILD}/src/my-scene.axes)
build_and_expect(TRUE FALSE "rebuild after touching a user axis file (same content: nothing to recompile)")
build_and_expect(FALSE FALSE "no-op rebuild after the touch")
file(APPEND ${BUILD}/src/my-scene.axes "0.5 0.25 1\n")
build_and_expect(TRUE TRUE "rebuild after adding an axis to a user axis file")
if(KDOP_GEN)
  touch_later(${KDOP_GEN})
  build_and_expect(TRUE FALSE "rebuild after kdop-gen (with its built-in sets and templates) changed")
endif()
build_and_expect(FALSE FALSE "final no-op rebuild")
