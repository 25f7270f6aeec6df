# The capture commands as a user meets them, end to end:
#   record a noisy scripted performance as a trajectory CSV with a plot and a report,
#   run the simulation from that CSV,
#   write a synthetic depth session as a fakenect recording and run the simulation from it (through
#   libfreenect's fakenect library), record it again as a trajectory and as a second fakenect recording,
#   and check that a truncated recording is refused with a clear message.
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})

function(run_ok)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(out "${out}${err}" PARENT_SCOPE)
endfunction()

function(expect_file path)
  if(NOT EXISTS ${path})
    message(FATAL_ERROR "missing ${path}")
  endif()
endfunction()

set(run_args --particles 400 --ply-every 0 --images-every 0 --no-progress --backend cpu --no-render)

# A scripted performance seen through noise, kept as a trajectory.
run_ok(${EXE} record --input script:circles --noise 0.01 --outliers 0.03 --trajectory ${OUT}/hands.csv
       --plot ${OUT}/hands.svg --report)
expect_file(${OUT}/hands.svg)
if(NOT out MATCHES "bspline +[0-9.]+ +[0-9.]+ +[0-9.]+x")
  message(FATAL_ERROR "no jitter report:\n${out}")
endif()
file(STRINGS ${OUT}/hands.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 123)  # comment + header + 121 samples (4 s at 30 Hz)
  message(FATAL_ERROR "hands.csv has ${n} lines, expected 123")
endif()

# The simulation driven by it, for its own length (4 s) unless told otherwise.
run_ok(${EXE} run --input trajectory:${OUT}/hands.csv --duration 0.2 --out ${OUT}/run_trajectory ${run_args})
expect_file(${OUT}/run_trajectory/wands.svg)
file(STRINGS ${OUT}/run_trajectory/wands.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 12)  # header + frame 0 + 10 frames
  message(FATAL_ERROR "wands.csv has ${n} lines, expected 12")
endif()

# A synthetic depth session, played through libfreenect's fakenect library.
run_ok(${MAKE_RECORDING} ${OUT}/session 9)
run_ok(${EXE} run --input fakenect:${OUT}/session --out ${OUT}/run_fakenect ${run_args})
if(NOT out MATCHES "input: fakenect recording .*9 depth frames")
  message(FATAL_ERROR "the run did not read the recording:\n${out}")
endif()
if(NOT out MATCHES "simulated +0.26 s")  # the recording's length, 8 frame times at 30 Hz, in 0.02 s frames
  message(FATAL_ERROR "the run did not take the recording's length:\n${out}")
endif()
run_ok(${EXE} record --input fakenect:${OUT}/session --trajectory ${OUT}/session.csv --fakenect ${OUT}/again)
file(STRINGS ${OUT}/session.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 11)
  message(FATAL_ERROR "session.csv has ${n} lines, expected 11:\n${rows}")
endif()
list(GET rows 2 first)
if(NOT first MATCHES "^0.000000(,-?[0-9]+\\.[0-9]+)(,-?[0-9]+\\.[0-9]+)(,-?[0-9]+\\.[0-9]+)(,-?[0-9]+\\.[0-9]+)(,-?[0-9]+\\.[0-9]+)(,-?[0-9]+\\.[0-9]+)$")
  message(FATAL_ERROR "the first sample does not have both hands: ${first}")
endif()
file(STRINGS ${OUT}/again/INDEX.txt frames)
list(LENGTH frames n)
if(NOT n EQUAL 9)
  message(FATAL_ERROR "the re-recording has ${n} frames, expected 9")
endif()

# A truncated recording is refused before playback, with the file and the reason.
run_ok(${MAKE_RECORDING} ${OUT}/truncated 3 --truncate)
execute_process(COMMAND ${EXE} run --input fakenect:${OUT}/truncated --out ${OUT}/run_truncated ${run_args}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "error: fakenect recording .*INDEX.txt line 3: depth file .* is truncated")
  message(FATAL_ERROR "a truncated recording was not refused clearly (${rc}):\n${out}\n${err}")
endif()

# A performer who walks in late: the room is empty for 0.5 s. The run waits, says why once per
# second, and makes the film when both hands are found: stats.csv's frame 0 says so, and the film's first area
# is the rest pose's (a scripted run's first frame) within 10%: the detected hands stand 0.5 m apart, as the
# rest pose's tips do after the reach, each within a few centimetres of its true centre.
run_ok(${MAKE_RECORDING} ${OUT}/late 30 --nobody-until 0.5)
run_ok(${EXE} run --input fakenect:${OUT}/late --out ${OUT}/run_late ${run_args})
if(NOT out MATCHES "waiting for a performer: no body in the depth band 0.5-4.0 m")
  message(FATAL_ERROR "no message while nobody was in view:\n${out}")
endif()
if(NOT out MATCHES "performer found after 0.50 s of input")
  message(FATAL_ERROR "the performer was not reported found at 0.5 s:\n${out}")
endif()
file(STRINGS ${OUT}/run_late/stats.csv late_rows)
list(GET late_rows 1 late_first)
if(NOT late_first MATCHES "performer_found film_created")
  message(FATAL_ERROR "stats.csv frame 0 does not say when the performer was found: ${late_first}")
endif()
run_ok(${EXE} run --gesture straight --duration 0.02 --out ${OUT}/run_rest ${run_args})
file(STRINGS ${OUT}/run_rest/stats.csv rest_rows)
list(GET rest_rows 1 rest_first)
string(REPLACE "," ";" late_fields "${late_first}")
string(REPLACE "," ";" rest_fields "${rest_first}")
list(GET late_fields 4 late_area)
list(GET rest_fields 4 rest_area)
execute_process(COMMAND awk "BEGIN { r = ${late_area} / ${rest_area}; exit !(r > 0.9 && r < 1.1) }" RESULT_VARIABLE ratio_rc)
if(NOT ratio_rc EQUAL 0)
  message(FATAL_ERROR "the film's first area ${late_area} m^2 is not the rest pose's ${rest_area} m^2 within 10%")
endif()
message(STATUS "late performer: first film area ${late_area} m^2, rest pose ${rest_area} m^2")
