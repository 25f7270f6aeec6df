# `giantbubble run --render` headless: writes rendered PNG frames next to the stats and, ffmpeg installed, an MP4
# with one video frame per simulation frame (--video-fps 50, the simulation's rate), then one every second frame at
# 25 frames/s (--video-fps 25), the PNG frames drawn whether the video takes them or not. BACKEND vulkan also checks that the renderer reads the stepper's
# buffers in place.
file(REMOVE_RECURSE ${OUT})
include(${CMAKE_CURRENT_LIST_DIR}/cli_run_giantbubble.cmake)
run_giantbubble(run --duration 0.1 --particles 400 --ply-every 0 --images-every 0 --out ${OUT} --no-progress
                --backend ${BACKEND} --render --width 160 --height 90 --render-every 2 --video-fps 50)
if(skipped)
  return()
endif()
expect_files(${OUT} stats.csv render_00000.png render_00002.png render_00004.png)
if(EXISTS ${OUT}/render_00001.png)
  message(FATAL_ERROR "--render-every 2 wrote frame 1")
endif()
# How much of the step the render overlapped, from the device's timestamps: timed wherever the device's clock can be
# read on the host's (lavapipe can), and said so where not.
file(READ ${OUT}/stats.json stats)
string(JSON render_type ERROR_VARIABLE no_overlap TYPE "${stats}" step_render_overlap render_s)
if(no_overlap)
  message(FATAL_ERROR "stats.json has no step_render_overlap.render_s: ${no_overlap}")
endif()
if(render_type STREQUAL "NUMBER")
  string(JSON render_s GET "${stats}" step_render_overlap render_s)
  if(NOT render_s GREATER 0 OR NOT out MATCHES "step and render overlap +[0-9.]+ s of")
    message(FATAL_ERROR "the render was timed at ${render_s} s, or the summary does not say the overlap:\n${out}")
  endif()
elseif(NOT out MATCHES "step and render overlap +not timed")
  message(FATAL_ERROR "the render was not timed and the summary does not say so:\n${out}")
endif()
if(BACKEND STREQUAL "vulkan" AND NOT out MATCHES "from the Vulkan stepper's buffers, copied on the device")
  message(FATAL_ERROR "the renderer did not read the Vulkan stepper's buffers in place:\n${out}")
endif()
find_program(FFPROBE ffprobe)
if(FFPROBE)
  execute_process(COMMAND ${FFPROBE} -v error -count_frames -show_entries stream=width,height,nb_read_frames -of csv=p=0
                          ${OUT}/render.mp4 OUTPUT_VARIABLE probe RESULT_VARIABLE prc)
  string(STRIP "${probe}" probe)
  if(NOT prc EQUAL 0 OR NOT probe STREQUAL "160,90,6")  # frame 0 + 5 frames
    message(FATAL_ERROR "render.mp4 is not 6 frames of 160x90: '${probe}'\n${out}")
  endif()
  run_giantbubble(run --duration 0.1 --particles 400 --ply-every 0 --images-every 0 --out ${OUT}/half --no-progress
                  --backend ${BACKEND} --render --width 160 --height 90 --render-every 3 --video-fps 25)
  expect_files(${OUT}/half render_00003.png)
  execute_process(COMMAND ${FFPROBE} -v error -count_frames -show_entries stream=r_frame_rate,nb_read_frames -of csv=p=0
                          ${OUT}/half/render.mp4 OUTPUT_VARIABLE probe RESULT_VARIABLE prc)
  string(STRIP "${probe}" probe)
  if(NOT prc EQUAL 0 OR NOT probe STREQUAL "25/1,3")  # frames 0, 2 and 4
    message(FATAL_ERROR "--video-fps 25: render.mp4 is not 3 frames at 25/1: '${probe}'\n${out}")
  endif()
else()
  message(WARNING "*** ffprobe not installed: the MP4 was not checked ***")
endif()
