# A short run on the Vulkan backend with the work between steps on the device (--between-steps device): the film
# hangs still before the stroke, no rule between steps acts, and the frames bring no state back; the summary and
# stats.json's readback say so (docs/backends.md). Rendered, the same: the renderer draws the device's buffers in
# place and frames the film from its positions alone.
file(REMOVE_RECURSE ${OUT})
include(${CMAKE_CURRENT_LIST_DIR}/cli_run_giantbubble.cmake)
foreach(rendering no-render render)
  run_giantbubble(run --duration 0.4 --particles 400 --ply-every 0 --images-every 0 --out ${OUT}/${rendering}
                  --no-progress --backend vulkan --between-steps device --${rendering} --width 64 --height 36)
  if(skipped)
    return()
  endif()
  file(READ ${OUT}/${rendering}/stats.json stats)
  string(JSON frames GET ${stats} readback frames)
  string(JSON passed GET ${stats} readback frames_passed_by_checks)
  string(JSON readbacks GET ${stats} readback state_readbacks)
  math(EXPR accounted "${passed} + ${readbacks}")
  string(JSON held TYPE ${stats} readback frames_held_by_rule)
  if(NOT held STREQUAL "OBJECT")
    message(FATAL_ERROR "${rendering}: stats.json's readback has no frames_held_by_rule:\n${stats}")
  endif()
  # Every frame either passed the checks or brought the state back; a film hanging still passes most (all 20 on
  # lavapipe): a few may come near a threshold on another device's rounding.
  if(NOT frames EQUAL 20 OR NOT accounted EQUAL frames OR passed LESS 15)
    message(FATAL_ERROR "${rendering}: of ${frames} frames ${passed} passed the device's checks, ${readbacks} read "
                        "the state back:\n${stats}")
  endif()
  if(NOT out MATCHES "passed by the device's checks")
    message(FATAL_ERROR "the summary does not say what came back from the device:\n${out}")
  endif()
endforeach()
# Asked for a place that is not one, the run fails naming the choices.
execute_process(COMMAND ${EXE} run --between-steps gpu --out ${OUT}/none RESULT_VARIABLE rc ERROR_VARIABLE e
                OUTPUT_VARIABLE o)
if(rc EQUAL 0 OR NOT "${o}${e}" MATCHES "between-steps")
  message(FATAL_ERROR "--between-steps gpu was taken (${rc}):\n${o}\n${e}")
endif()
