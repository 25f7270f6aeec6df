# run_giantbubble(<args>...): runs ${EXE} with the arguments into `out` and `err` in the caller's scope. A run
# that failed for want of a Vulkan device is skipped loudly outside CI (sets `skipped` to TRUE); any other
# failure stops the test with the output.
function(run_giantbubble)
  execute_process(COMMAND ${EXE} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  set(out "${o}" PARENT_SCOPE)
  set(err "${e}" PARENT_SCOPE)
  set(skipped FALSE PARENT_SCOPE)
  if(NOT rc EQUAL 0 AND e MATCHES "no Vulkan device|Vulkan could not start|needs a Vulkan device" AND NOT "$ENV{CI}" STREQUAL "true")
    message(WARNING "*** SKIPPING: ${e} ***")
    set(skipped TRUE PARENT_SCOPE)
  elseif(NOT rc EQUAL 0)
    message(FATAL_ERROR "giantbubble ${ARGN} failed (${rc}):\n${o}\n${e}")
  endif()
endfunction()

# expect_files(<dir> <name>...): every named file exists in <dir>, else the test stops naming the first missing.
function(expect_files dir)
  foreach(f IN LISTS ARGN)
    if(NOT EXISTS ${dir}/${f})
      message(FATAL_ERROR "giantbubble did not write ${f} in ${dir}:\n${out}")
    endif()
  endforeach()
endfunction()
