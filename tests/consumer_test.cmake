# Builds examples/consumer against this kdop build tree, as an outside project would, runs it, and
# checks kdop_add_variants()'s dependencies: nothing regenerates on a no-op rebuild; editing a user
# axis file or rebuilding kdop-gen regenerates.
# Inputs: SOURCE, BUILD, kdop_DIR, GENERATOR, KDOP_GEN.

function(run_checked output_var)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${out}\n${err}")
  endif()
  set(${output_var} "${out}${err}" PARENT_SCOPE)
endfunction()

function(build_and_expect_generation expected reason)
  run_checked(out ${CMAKE_COMMAND} --build ${BUILD}/build)
  string(FIND "${out}" "kdop: generating" found)
  if(expected AND found EQUAL -1)
    message(FATAL_ERROR "${reason}: expected the variants to be regenerated, build said:\n${out}")
  elseif(NOT expected AND NOT found EQUAL -1)
    message(FATAL_ERROR "${reason}: expected no regeneration, build said:\n${out}")
  endif()
  message(STATUS "ok: ${reason}")
endfunction()

# Work on a copy, so touching its axis file does not touch the repository.
file(REMOVE_RECURSE ${BUILD})
file(COPY ${SOURCE}/ DESTINATION ${BUILD}/src)

run_checked(out ${CMAKE_COMMAND} -S ${BUILD}/src -B ${BUILD}/build -G ${GENERATOR} -Dkdop_DIR=${kdop_DIR})
build_and_expect_generation(TRUE "first build")

run_checked(out ${BUILD}/build/consumer dop22-clip-n9)
if(NOT out MATCHES "found dop22-clip-n9 \\(clip, 11 axes\\): usable")
  message(FATAL_ERROR "consumer did not find dop22-clip-n9:\n${out}")
endif()
run_checked(out ${BUILD}/build/consumer my-scene-clip-n9)
if(NOT out MATCHES "found my-scene-clip-n9 \\(clip, 7 axes\\): usable")
  message(FATAL_ERROR "consumer did not find my-scene-clip-n9:\n${out}")
endif()
execute_process(COMMAND ${BUILD}/build/consumer dop32-clip-n9 RESULT_VARIABLE result OUTPUT_QUIET ERROR_QUIET)
if(result EQUAL 0)
  message(FATAL_ERROR "consumer claims a variant it was not built with")
endif()

build_and_expect_generation(FALSE "no-op rebuild")
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
file(TOUCH ${BUILD}/src/my-scene.axes)
build_and_expect_generation(TRUE "rebuild after editing a user axis file")
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
file(TOUCH ${KDOP_GEN})
build_and_expect_generation(TRUE "rebuild after kdop-gen (with its built-in sets and templates) changed")
build_and_expect_generation(FALSE "second no-op rebuild")
