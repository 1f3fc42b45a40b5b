cmake_minimum_required(VERSION 3.25)
# Builds examples/meson_consumer with Meson against an installation of this kdop build that was
# moved after installing, found through pkg-config alone: lib/pkgconfig/kdop.pc must name nothing
# outside the prefix, `pkg-config --cflags` must reach the headers, the kdop_gen variable the
# generator, and the Meson project must generate its registry, build, and pass its own test. The
# prefix holds a space, which pkg-config writes as "\ " in every path it gives (Meson's
# find_program failed on the kdop_gen variable so written).
# Inputs: SOURCE, BUILD, INSTALL_FROM (the kdop build directory), MESON, PKG_CONFIG.

include(${CMAKE_CURRENT_LIST_DIR}/project_test_support.cmake)

file(REMOVE_RECURSE ${BUILD})
file(COPY ${SOURCE}/ DESTINATION ${BUILD}/src)
run_checked(out ${CMAKE_COMMAND} --install ${INSTALL_FROM} --prefix ${BUILD}/staged)
file(RENAME ${BUILD}/staged "${BUILD}/pre fix")
file(GLOB_RECURSE pc_files "${BUILD}/pre fix/*.pc")
list(LENGTH pc_files pc_count)
if(NOT pc_count EQUAL 1)
  message(FATAL_ERROR "expected one installed .pc file, found: ${pc_files}")
endif()
get_filename_component(kdop_source "${SOURCE}/../.." ABSOLUTE)
expect_relocatable("${pc_files}" "${kdop_source};${INSTALL_FROM};${BUILD}/staged")
get_filename_component(pc_dir "${pc_files}" DIRECTORY)
set(env ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dir})

# A Makefile's view: the flags reach the headers, the variable the generator, the version is ours;
# a path's "\ " is a space as the shell that runs a Makefile's commands reads it.
run_checked(cflags ${env} ${PKG_CONFIG} --cflags kdop)
string(STRIP "${cflags}" cflags)
string(REPLACE "\\ " " " cflags "${cflags}")
string(REGEX REPLACE "^-I" "" include_dir "${cflags}")
if(NOT EXISTS "${include_dir}/kdop/variant.h")
  message(FATAL_ERROR "pkg-config --cflags kdop gave '${cflags}', which does not reach kdop/variant.h")
endif()
run_checked(kdop_gen ${env} ${PKG_CONFIG} --variable=kdop_gen kdop)
string(STRIP "${kdop_gen}" kdop_gen)
string(REPLACE "\\ " " " kdop_gen "${kdop_gen}")
run_checked(version ${kdop_gen} --version)
run_checked(modversion ${env} ${PKG_CONFIG} --modversion kdop)
string(STRIP "${modversion}" modversion)
if(NOT version MATCHES "kdop-gen ${modversion}")
  message(FATAL_ERROR "kdop.pc says version ${modversion}; its kdop-gen says ${version}")
endif()

run_checked(out ${env} ${MESON} setup ${BUILD}/build ${BUILD}/src)
run_checked(out ${env} ${MESON} compile -C ${BUILD}/build)
if(NOT out MATCHES "taa_kdop")
  message(FATAL_ERROR "meson compile did not generate the registry:\n${out}")
endif()
run_checked(out ${env} ${MESON} test -C ${BUILD}/build --print-errorlogs)
run_checked(out ${BUILD}/build/meson_consumer)
foreach(expected IN ITEMS "taa_resolve: compute shader, 3 binding" "set 0 binding 2: resolved_frame \\(storage image\\)"
                          "dop22-clip-n9: compute shader" "taa_resolve is reflected as declared")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "meson_consumer did not print '${expected}':\n${out}")
  endif()
endforeach()
if(NOT EXISTS ${BUILD}/build/taa_kdop.json)
  message(FATAL_ERROR "the Meson build did not write the registry's JSON")
endif()
# A rebuild with nothing changed runs nothing (the depfile and outputs hold).
run_checked(out ${env} ${MESON} compile -C ${BUILD}/build)
if(out MATCHES "kdop-gen|Generating")
  message(FATAL_ERROR "a no-op rebuild regenerated the registry:\n${out}")
endif()
message(STATUS "ok: built with Meson from a moved installation through pkg-config:\n${out}")
