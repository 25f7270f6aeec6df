# run --realtime behind the wall clock: lavapipe on two cores cannot draw 1920x1080 at 50 frames/s beside the step, so
# the frames are drawn smaller (RealTimePacer::renderScale), and every frame is still written at 1920x1080.
execute_process(
  COMMAND "${EXE}" run --realtime --duration 0.8 --ply-every 0 --images-every 0 --no-progress --backend cpu --render
          --width 1920 --height 1080 --render-every 40 --out "${OUT}"
  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "run --realtime --render failed (${rc}):\n${out}\n${err}")
endif()
if(NOT out MATCHES "render: behind the wall clock, [0-9]+ frames drawn smaller, down to [0-9]+% of 1440x810")
  message(FATAL_ERROR "the frames were not drawn smaller behind the wall clock:\n${out}")
endif()
# The PNG's width and height, big-endian in its IHDR chunk (bytes 16-23).
file(READ "${OUT}/render_00040.png" header LIMIT 24 HEX)
string(SUBSTRING "${header}" 32 8 width_hex)
string(SUBSTRING "${header}" 40 8 height_hex)
math(EXPR width "0x${width_hex}")
math(EXPR height "0x${height_hex}")
if(NOT width EQUAL 1920 OR NOT height EQUAL 1080)
  message(FATAL_ERROR "frame 40 was written at ${width}x${height}, not 1920x1080")
endif()
message(STATUS "${out}")
