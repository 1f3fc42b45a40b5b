# What the scripts that build example projects share (consumer_test.cmake, example_*_test.cmake).

# Runs a command; fails the test with its output unless it exits 0. OUTPUT_VAR gets stdout and stderr.
function(run_checked output_var)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${out}\n${err}")
  endif()
  set(${output_var} "${out}${err}" PARENT_SCOPE)
endfunction()

# Waits past the file system's time-stamp resolution, then touches FILE, so a build sees it newer.
function(touch_later file)
  execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
  file(TOUCH ${file})
endfunction()

# Fails unless none of FILES names any of the folders TREES: an installed package is relocatable
# only if it refers to nothing outside itself.
function(expect_relocatable files trees)
  foreach(file IN LISTS files)
    file(READ ${file} text)
    foreach(tree IN LISTS trees)
      string(FIND "${text}" "${tree}" found)
      if(NOT found EQUAL -1)
        message(FATAL_ERROR "${file} refers to ${tree}: the installed package is not relocatable")
      endif()
    endforeach()
  endforeach()
endfunction()
