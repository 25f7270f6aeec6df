#!/usr/bin/env bash
# Show-proofing on the command line, one case per ctest test:
#   cli_show_proof_test.sh EXE OUT CASE [FAKE_FREENECT MAKE_RECORDING]
# Each case prints what it checks and exits non-zero with the reason when the program does not do it. The cases on a
# camera take the stand-in for the live libfreenect (fake_freenect.cpp) and the synthetic recording's writer.
set -u
EXE=$1
OUT=$2
CASE=$3
FAKE=${4:-}
MAKE_RECORDING=${5:-}
rm -rf "$OUT"
mkdir -p "$OUT"
cd "$OUT" || exit 1
# --no-render: the default scene renders its video; the cases that want frames add RENDER after SMALL (the last wins).
# RENDER's video takes every simulation frame (--video-fps 50, the rate at h = 0.02 s; a CPU driver's own is 25), so
# that its frames are counted against the rows of stats.csv.
SMALL=(--particles 400 --backend cpu --ply-every 0 --images-every 0 --no-progress --no-render)
RENDER=(--render --width 64 --height 48 --render-every 0 --video-fps 50)

fail() {
  echo "FAIL: $*"
  exit 1
}

# Waits (at most 120 s) until FILE has at least N lines.
wait_for_lines() {
  for _ in $(seq 1200); do
    [ -f "$1" ] && [ "$(wc -l <"$1")" -ge "$2" ] && return 0
    sleep 0.1
  done
  fail "$1 never reached $2 lines"
}

# Waits (at most 120 s) until FILE holds TEXT.
wait_for_text() {
  for _ in $(seq 1200); do
    grep -qF -- "$2" "$1" 2>/dev/null && return 0
    sleep 0.1
  done
  fail "$1 never held $2"
}

# Frames in an MP4 as ffprobe decodes them (0 when it cannot be read).
mp4_frames() {
  ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$1" 2>/dev/null || echo 0
}

# A trajectory CSV: rows at the given times, both hands still in front of the camera.
trajectory() {
  echo "t,left_x,left_y,left_z,right_x,right_y,right_z"
  for t in "$@"; do echo "$t,-0.15,0,2,0.15,0,2"; done
}

# A signal mid-run: the frame in flight finishes, stats.json says "interrupted", stats.csv holds every frame
# done and the MP4 plays with the frames rendered. The input is a trajectory two hours long: the duration it
# gives is capped at 3600 s (180,000 frames) with a note, not taken whole.
signal_case() {
  local signal=$1 expected=$2
  trajectory 0 3600 7200 >long.csv
  "$EXE" run --input trajectory:long.csv "${SMALL[@]}" "${RENDER[@]}" --out run >log.txt 2>&1 &
  local pid=$!
  wait_for_lines run/stats.csv 8
  kill "-$signal" "$pid"
  wait "$pid"
  local rc=$?
  cat log.txt
  [ "$rc" -eq "$expected" ] || fail "exit status $rc after SIG$signal, expected $expected"
  grep -q "the run stops at 3600 s" log.txt || fail "no note that the input's duration was capped"
  grep -q "180000 frames" log.txt || fail "the run was not planned for 180000 frames"
  grep -q '"status": "interrupted"' run/stats.json || fail "stats.json does not say interrupted"
  local rows frames
  rows=$(($(wc -l <run/stats.csv) - 2))  # the header and frame 0
  frames=$(mp4_frames run/render.mp4)
  echo "frames simulated: $rows, frames in the MP4: $frames"
  [ "$frames" -eq $((rows + 1)) ] || fail "the MP4 has $frames frames, expected $((rows + 1)) (frame 0 and $rows)"
}

# Runs giantbubble ARGS and fails unless it exits 1 with MESSAGE in its output: expect_refused MESSAGE ARGS...
expect_refused() {
  local message=$1
  shift
  "$EXE" "$@" >log.txt 2>&1
  local rc=$?
  [ "$rc" -eq 1 ] || fail "giantbubble $*: exit status $rc, expected 1: $(cat log.txt)"
  grep -qF -- "$message" log.txt || fail "giantbubble $*: $(cat log.txt)"
  echo "giantbubble $*: $(grep -F -- "$message" log.txt | head -1)"
}

# Fails unless FILE is the same as its copy in saved/ (a run must not have touched it).
expect_unchanged() {
  cmp -s "$1" "saved/$(basename "$1")" || fail "$1 was changed by a run that failed: $(cat log.txt)"
}

case "$CASE" in
  sigint) signal_case INT 130 ;;
  sigterm) signal_case TERM 143 ;;
  sighup) signal_case HUP 129 ;; # a closed terminal
  failed_encoder)
    # An ffmpeg that fails at once: the run says so, goes on, and writes all its results (exit 5).
    mkdir fakebin
    printf '#!/bin/sh\necho "fake ffmpeg: cannot encode" >&2\nexit 1\n' >fakebin/ffmpeg
    chmod +x fakebin/ffmpeg
    PATH="$OUT/fakebin:$PATH" "$EXE" run --duration 0.2 "${SMALL[@]}" "${RENDER[@]}" --out run 2>&1 | tee log.txt
    rc=${PIPESTATUS[0]}
    [ "$rc" -eq 5 ] || fail "exit status $rc, expected 5"
    grep -q "warning: video: ffmpeg stopped taking frames" log.txt || fail "the failed encoder was not reported"
    grep -q '"status": "finished"' run/stats.json || fail "stats.json missing or not finished"
    grep -q '"video_error"' run/stats.json || fail "stats.json does not note the video error"
    [ "$(wc -l <run/stats.csv)" -eq 12 ] || fail "stats.csv does not have the header and frames 0 to 10"
    ;;
  any_path)
    # Quotes and spaces in the output folder; a video name that would run a command through a shell.
    "$EXE" run --duration 0.1 "${SMALL[@]}" "${RENDER[@]}" --out "bob's show" || fail "run into \"bob's show\" failed"
    [ "$(mp4_frames "bob's show/render.mp4")" -eq 6 ] || fail "no 6-frame MP4 in \"bob's show\""
    "$EXE" run --duration 0.1 "${SMALL[@]}" "${RENDER[@]}" --out run --video "x';touch pwned;'.mp4" || fail "run failed"
    [ ! -e pwned ] && [ ! -e run/pwned ] || fail "the video name ran a command"
    [ "$(mp4_frames "run/x';touch pwned;'.mp4")" -eq 6 ] || fail "the video was not written under its own name"
    "$EXE" run --duration 0.1 "${SMALL[@]}" "${RENDER[@]}" --out run --video "sub folder/show.mp4" || fail "run failed"
    [ "$(mp4_frames "run/sub folder/show.mp4")" -eq 6 ] || fail "--video into a new folder was not written"
    ;;
  full_disk)
    # Every file limited to 40 KiB (RLIMIT_FSIZE; SIGXFSZ ignored so the write fails as on a full disk): the run
    # stops with an error naming the file, not a cut row and exit 0.
    (
      ulimit -f 40
      trap '' XFSZ
      exec "$EXE" run --duration 10 "${SMALL[@]}" --out run
    ) >log.txt 2>&1
    rc=$?
    cat log.txt
    [ "$rc" -ne 0 ] || fail "exit status 0 on a full disk"
    grep -Eq "error: failed writing .*(stats|wands)\.csv: File too large" log.txt || fail "the file is not named"
    ;;
  bench_json)
    "$EXE" bench --sizes 500 --backends cpu --steps 8 --json /nonexistent/bench.json >log.txt 2>&1
    rc=$?
    cat log.txt
    [ "$rc" -ne 0 ] || fail "bench --json into a missing folder exited 0"
    grep -q "error: --json: cannot write /nonexistent/bench.json: No such file or directory" log.txt ||
      fail "the unwritable path is not named"
    grep -q "measuring" log.txt && fail "the path was checked after measuring, not before"
    grep -q "results written" log.txt && fail "says the results were written"
    ;;
  not_finite)
    for args in "--duration nan" "--speed nan" "--reach nan" "--camera-pitch nan" "--solution nan" \
      "--depth-band nan 2" "--burst-at inf" "--duration -inf" "--video-fps nan" "--render-scale nan"; do
      # shellcheck disable=SC2086
      "$EXE" run $args --out run >log.txt 2>&1
      rc=$?
      [ "$rc" -ne 0 ] || fail "run $args exited 0"
      grep -q "is not a finite number" log.txt || fail "run $args: $(cat log.txt)"
      echo "run $args: $(head -1 log.txt)"
    done
    ;;
  scene_not_a_file)
    "$EXE" run --scene "$OUT" >log.txt 2>&1 && fail "--scene on a folder exited 0"
    grep -q "is a folder" log.txt || fail "--scene on a folder: $(cat log.txt)"
    mkfifo scene.toml
    timeout 20 "$EXE" run --scene ./scene.toml >log.txt 2>&1
    rc=$?
    [ "$rc" -ne 124 ] || fail "--scene on a FIFO blocked"
    grep -q "is a FIFO (a scene is read from a regular file)" log.txt || fail "--scene on a FIFO: $(cat log.txt)"
    ;;
  keys_overflow)
    "$EXE" live --keys 99999999999999999999:b >log.txt 2>&1 && fail "exited 0"
    grep -q "frame 99999999999999999999 is too large" log.txt || fail "$(cat log.txt)"
    ;;
  dense_trajectory)
    trajectory 0 0.000000001 >dense.csv
    timeout 120 "$EXE" run --input trajectory:dense.csv --duration 5 "${SMALL[@]}" --out run >log.txt 2>&1
    rc=$?
    [ "$rc" -eq 0 ] || fail "exit status $rc (124: it stalled) $(cat log.txt)"
    ;;
  no_poke_on_recordings)
    # A scene's poke is for its scripted gesture: not on a recorded performance, unless asked. (The default
    # scene has no poke; fig11a pokes at 2.5 s.)
    trajectory $(seq 0 0.1 4.5) >hands.csv
    "$EXE" run --scene fig11a --input trajectory:hands.csv "${SMALL[@]}" --out run >log.txt 2>&1 || fail "$(cat log.txt)"
    grep -q "note: no poke at" log.txt || fail "no note about the poke"
    grep -q poked run/stats.csv && fail "the scene's poke fired on a trajectory"
    "$EXE" run --input trajectory:hands.csv --burst-at 1 "${SMALL[@]}" --out run >log.txt 2>&1 || fail "$(cat log.txt)"
    # Poked at frame 50 exactly (1 s at 50 frames/s), counted, not compared as floats.
    grep -q "^50,.*poked" run/stats.csv || fail "--burst-at 1 did not poke at frame 50"
    ;;
  live_input_ends)
    # A live show whose input (a file) ends: the wands rest with their film, the show goes on to the end of --frames.
    trajectory $(seq 0 0.1 0.5) >short.csv
    xvfb-run -a "$EXE" live --input trajectory:short.csv --frames 60 --width 160 --height 120 --particles 400 \
      --backend cpu --osc 127.0.0.1:9 >log.txt 2>&1
    rc=$?
    cat log.txt
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    grep -q "the input has played to its end; the wands rest" log.txt || fail "the end of the input was not said"
    grep -q "presented 60 frames" log.txt || fail "the show did not go on"
    ;;
  live_unstable)
    # A live show whose simulation blows up: the explicit reference integrator at its bare stability bound
    # (stabilitySafety 1) with an air pressure gain a thousand times the default (the bound holds the coupling's
    # damping, not its turning with the film's normals: it blows up in the first frame; the implicit default stays
    # stable there): reported, a new film, and the show goes on to the end of --frames.
    xvfb-run -a "$EXE" live --frames 50 --width 160 --height 120 --particles 400 --backend cpu --fixed-step \
      --param integrator=0 --param airPressureGain=10000 --param pressureCoefficient=10000000 \
      --param stabilitySafety=1 --osc 127.0.0.1:9 >log.txt 2>&1
    rc=$?
    cat log.txt
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    grep -q "the simulation became unstable; a new film is dipped" log.txt || fail "no recovery reported"
    grep -q "presented 50 frames" log.txt || fail "the show did not go on"
    ;;
  outputs_only_onto_files)
    # A FIFO or a folder where an output goes is refused by name, left as it was, and nothing blocks on the FIFO. (A
    # device is the same case; it is checked in ShowProof.AnOutputIsNeverWrittenOntoAFifoAFolderOrADevice without
    # writing to one: as root, the old rename replaced /dev/null.)
    mkfifo fifo.json
    mkdir folder.json
    for target in fifo.json folder.json; do
      timeout 120 "$EXE" bench --sizes 100 --backends cpu --steps 8 --json $target >log.txt 2>&1
      rc=$?
      cat log.txt
      [ "$rc" -eq 1 ] || fail "bench --json $target: exit status $rc"
      grep -q "error: --json: will not write $target: it is a" log.txt ||
        fail "bench --json $target: the problem is not named"
      grep -q "results written\|Success" log.txt && fail "bench --json $target: says it succeeded"
    done
    [ -p fifo.json ] && [ -d folder.json ] || fail "the FIFO or the folder was replaced"
    mkdir run
    mkfifo run/stats.csv
    timeout 120 "$EXE" run --duration 0.1 "${SMALL[@]}" --out run >log.txt 2>&1
    rc=$?
    cat log.txt
    [ "$rc" -eq 1 ] || fail "a run onto a FIFO stats.csv: exit status $rc (124: it blocked)"
    grep -q "will not write run/stats.csv: it is a FIFO" log.txt || fail "the FIFO stats.csv is not named"
    ;;
  two_runs_one_folder)
    # A second run into the folder of a run that is going on is refused, naming the first; the first's rows stay whole.
    trajectory 0 3600 7200 >long.csv
    "$EXE" run --input trajectory:long.csv "${SMALL[@]}" --out same >first.txt 2>&1 &
    first=$!
    wait_for_lines same/stats.csv 4
    "$EXE" run --scene fig10c "${SMALL[@]}" --duration 0.1 --out same >log.txt 2>&1
    rc=$?
    cat log.txt
    kill -INT "$first"
    wait "$first"
    [ "$rc" -eq 1 ] || fail "the second run into the same folder: exit status $rc"
    grep -q "error: another run is writing into same (process $first: .*giantbubble run --input trajectory:long.csv" \
      log.txt || fail "the first run is not named"
    grep -q '"scene": "default"' same/stats.json || fail "stats.json is not the first run's"
    awk -F, 'NR > 1 && NF != 22 { bad = 1 } END { exit bad }' same/stats.csv || fail "stats.csv has rows cut or mixed"
    ;;
  failed_run_keeps_previous)
    # A run refused for its input, its OSC target or its environment image leaves the previous run's files as they
    # were; one killed outright leaves stats.json saying "running", one stopped by a full disk "failed: ...".
    "$EXE" run --duration 0.1 "${SMALL[@]}" --out run >log.txt 2>&1 || fail "the first run failed: $(cat log.txt)"
    mkdir saved
    cp run/stats.json run/stats.csv run/wands.csv saved/
    echo "t,left_x,left_y,left_z,right_x,right_y,right_z" >far.csv
    echo "0,-1000000,0,2,1000000,0,2" >>far.csv
    echo "not a picture" >sky.png
    for bad in "--input trajectory:far.csv" "--osc no-port-here" "--render --environment sky.png"; do
      # shellcheck disable=SC2086
      "$EXE" run --duration 0.1 "${SMALL[@]}" $bad --out run >log.txt 2>&1 && fail "run $bad exited 0"
      echo "run $bad: $(grep error log.txt)"
      for file in run/stats.json run/stats.csv run/wands.csv; do expect_unchanged $file; done
    done
    trajectory 0 3600 7200 >long.csv
    "$EXE" run --input trajectory:long.csv "${SMALL[@]}" --out run >log.txt 2>&1 &
    pid=$!
    wait_for_text run/stats.json '"status": "running"'
    kill -KILL "$pid"
    wait "$pid"
    grep -q '"status": "running"' run/stats.json || fail "a run killed outright left stats.json: $(cat run/stats.json)"
    (
      ulimit -f 40
      trap '' XFSZ
      exec "$EXE" run --duration 10 "${SMALL[@]}" --out run
    ) >log.txt 2>&1 && fail "a run on a full disk exited 0"
    grep -Eq '"status": "failed: failed writing run/(stats|wands)\.csv: File too large"' run/stats.json ||
      fail "a run stopped by a full disk left stats.json: $(cat run/stats.json)"
    ;;
  default_scene_renders)
    # The default scene says what it renders ([render] in scenes/default.toml): any run of it makes its video, not
    # only `giantbubble run` without an option; options change it, and --no-render turns it off.
    "$EXE" run --duration 0.1 --particles 400 --backend cpu --ply-every 0 --images-every 0 --no-progress \
      --width 64 --height 48 --out run >log.txt 2>&1 || fail "$(cat log.txt)"
    # Frames 0 to 5, a video frame every STRIDE of them as the run says (2 on a CPU driver, 1 on a GPU).
    stride=$(sed -n 's/^render: video at .* (every \([0-9]*\) frames, --video-fps)$/\1/p' log.txt)
    grep -q "^render: video at 50 frames/s (every frame, --video-fps)$" log.txt && stride=1
    [ -n "$stride" ] || fail "the run does not say its video's rate: $(cat log.txt)"
    [ "$(mp4_frames run/render.mp4)" -eq $((5 / stride + 1)) ] ||
      fail "render.mp4 has not a frame every $stride of 6: $(cat log.txt)"
    [ -f run/render_00000.png ] && [ ! -f run/render_00001.png ] || fail "not a rendered PNG every 25 frames"
    "$EXE" run --duration 0.1 "${SMALL[@]}" --out quiet >log.txt 2>&1 || fail "$(cat log.txt)"
    [ ! -e quiet/render.mp4 ] || fail "--no-render made a video"
    ;;
  experiment_options)
    # A physics experiment builds its own film and runs its own length: an option it would ignore is refused by name,
    # and Ctrl-C ends it as it ends a run.
    for args in "--scene catenoid --duration 0.001" "--scene catenoid --input script:circles" \
      "--scene waves --tool ring" "--scene catenoid --particles 5000" "--scene waves --osc 127.0.0.1:9"; do
      # shellcheck disable=SC2086
      "$EXE" run $args --out run >log.txt 2>&1
      rc=$?
      echo "run $args: $(head -1 log.txt)"
      [ "$rc" -eq 1 ] || fail "run $args: exit status $rc"
      grep -q "does not apply to the physics experiment" log.txt || fail "run $args: $(cat log.txt)"
    done
    "$EXE" run --scene minimal-surface --particles 50000 --out run >log.txt 2>&1 &
    pid=$!
    for _ in $(seq 600); do grep -q "experiment minimal-surface" log.txt && break; sleep 0.1; done
    kill -INT "$pid"
    wait "$pid"
    rc=$?
    cat log.txt
    [ "$rc" -eq 130 ] || fail "the experiment after SIGINT: exit status $rc, expected 130"
    grep -q "SIGINT: the experiment minimal-surface stopped at t = " log.txt || fail "the stop is not said"
    grep -q '"status": "interrupted"' run/experiment.json || fail "experiment.json does not say interrupted"
    ;;
  exit_codes)
    # One table (docs/user-guide.md, "Exit status"): a mistake on the command line or in a scene is an error, 1.
    expect_exit() {
      local expected=$1
      shift
      "$EXE" "$@" >log.txt 2>&1
      local rc=$?
      [ "$rc" -eq "$expected" ] || fail "giantbubble $*: exit status $rc, expected $expected: $(cat log.txt)"
    }
    expect_exit 0 run --help
    expect_exit 1 run --no-such-option
    expect_exit 1 run --particles 99999999
    expect_exit 1 run --scene no-such-scene
    expect_exit 1 bench --sizes 10
    expect_exit 1 run --duration 0.1 "${SMALL[@]}" --out ''
    grep -q "error: --out: the name is empty: give a folder" log.txt || fail "--out '': $(cat log.txt)"
    ;;
  messages_name_the_problem)
    # Each message names the real problem and the option or file to change.
    expect_refused "trajectory file /dev/zero: is a character device" run --input trajectory:/dev/zero --out run
    expect_refused "--particles, --solution) is too few for its wire" run --solution 0.01 --particles 300 \
      --backend cpu --no-render --out run
    expect_refused "IPv6 is not supported" run --osc "[::1]:9000" --out run
    expect_refused "IPv6 is not supported" run --osc 127.0.0.1:9000:1 --out run
    expect_refused "particlesAtFullSolution = 2000000000 is out of range [16, 2000000]" run \
      --param particlesAtFullSolution=2e9
    expect_refused "particlesAtFullSolution = 10000000 is out of range [16, 2000000]" run \
      --param particlesAtFullSolution=10000000
    expect_refused "frameTime = 1e-50 is out of range [1e-05, 0.1] s" run --param frameTime=1e-50
    expect_refused "--keys -5:b: frame -5 is negative" live --keys -5:b
    expect_refused "--depth-plot-frame" record --input script:circles --depth-plot-frame -5 --report
    trajectory 0 1e308 >forever.csv
    expect_refused "line 3: time 1e308 s is 1e+308 s after the previous row's (at most 3600 s between rows)" run \
      --input trajectory:forever.csv --out run
    ;;
  long_trajectory_read_as_far_as_the_run)
    # 200,000 rows (about 17 minutes at 200 per second) for a 0.1 s run: read to the run's end (and a second for the
    # stabilizer), with a note, not parsed whole.
    awk 'BEGIN { print "t,left_x,left_y,left_z,right_x,right_y,right_z"; for (k = 0; k < 200000; ++k) printf "%.3f,-0.15,0,2,0.15,0,2\n", k * 0.005 }' >long.csv
    "$EXE" run --input trajectory:long.csv --duration 0.1 "${SMALL[@]}" --out run >log.txt 2>&1 || fail "$(cat log.txt)"
    grep -q "note: trajectory file long.csv, line 224: past the run's end; the rows from here are not read" log.txt ||
      fail "no note that the rest was not read: $(cat log.txt)"
    grep -q "(222 samples, 1.10 s)" log.txt || fail "not read to the run's end and a second: $(cat log.txt)"
    ;;
  terminal_injection)
    # A scene's name is printed: one holding a newline and an escape sequence is refused, and the message escapes them.
    printf 'name = "show\\n\\u001b[31mred"\n' >scene.toml
    "$EXE" run --scene ./scene.toml --out run >log.txt 2>&1 && fail "a name with control characters was taken"
    cat log.txt
    grep -qF "name = 'show\n\x1b[31mred' holds control characters" log.txt || fail "the name is not named"
    grep -q "$(printf '\033')" log.txt && fail "an escape sequence reached the terminal"
    ;;
  burst_with_no_film)
    # B when the film is gone says so instead of "burst".
    xvfb-run -a "$EXE" live --scene fig11a --frames 120 --width 160 --height 120 --particles 400 --backend cpu \
      --fixed-step --auto-dip -1 --keys 5:b 110:b >log.txt 2>&1
    rc=$?
    cat log.txt
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    grep -q "frame 5: burst" log.txt || fail "the first B did not burst the film"
    grep -q "frame 110: B: no film to burst" log.txt || fail "B with no film is not said"
    ;;
  record_outputs_as_runs)
    # record writes as run does: a trajectory that cannot be written whole leaves the old one and names the file and
    # the reason; a FIFO or a device is refused before anything is recorded; two outputs on one file, a file inside
    # the fakenect folder and a name whose extension is another format are refused, and nothing is written.
    trajectory 0 0.1 0.2 >t.csv
    mkdir saved
    cp t.csv saved/
    (
      ulimit -f 4
      trap '' XFSZ
      exec "$EXE" record --input script:circles --trajectory t.csv
    ) >log.txt 2>&1 && fail "a recording on a full disk exited 0"
    cat log.txt
    grep -q "error: failed writing t.csv: File too large" log.txt || fail "the file and the reason are not named"
    expect_unchanged t.csv
    [ ! -e t.csv.partial ] || fail "t.csv.partial was left"
    mkfifo fifo.csv
    ln -s /dev/null null.csv
    for target in fifo.csv null.csv; do
      timeout 20 "$EXE" record --input script:circles --trajectory $target >log.txt 2>&1
      rc=$?
      [ "$rc" -eq 1 ] || fail "--trajectory $target: exit status $rc (124: it blocked)"
      grep -q "error: --trajectory: will not write $target: it is a" log.txt ||
        fail "--trajectory $target: $(cat log.txt)"
      grep -q "recording from" log.txt && fail "--trajectory $target: refused only after recording"
    done
    [ -p fifo.csv ] && [ -c /dev/null ] || fail "the FIFO or /dev/null was replaced"
    RECORD=(record --input script:circles)
    expect_refused "error: --plot: t.csv does not end in .svg" "${RECORD[@]}" --trajectory t.csv --plot t.csv
    expect_unchanged t.csv
    ln -s t.csv plot.svg
    expect_refused "error: --trajectory t.csv and --plot plot.svg are one file" "${RECORD[@]}" --trajectory t.csv \
      --plot plot.svg
    expect_refused "error: --trajectory rec/hands.csv is inside --fakenect rec, which the command fills" \
      "${RECORD[@]}" --fakenect rec --trajectory rec/hands.csv
    expect_refused "error: --trajectory: rec/INDEX.txt does not end in .csv" "${RECORD[@]}" --fakenect rec \
      --trajectory rec/INDEX.txt
    expect_refused "error: --depth-plot: x.svg does not end in .png" "${RECORD[@]}" --depth-plot x.svg
    expect_refused "error: --plot: x.png does not end in .svg" "${RECORD[@]}" --plot x.png
    [ ! -e rec ] && [ ! -e x.svg ] && [ ! -e x.png ] || fail "a refused recording wrote something"
    expect_unchanged t.csv
    ;;
  outputs_into_a_held_folder)
    # A command writing into the folder of a run going on is refused, naming the run; two runs into other folders
    # with one video are refused as one file another process writes. The first run's files stay whole.
    trajectory 0 3600 7200 >long.csv
    "$EXE" run --input trajectory:long.csv "${SMALL[@]}" "${RENDER[@]}" --video "$OUT/show.mp4" --out same \
      >first.txt 2>&1 &
    first=$!
    wait_for_lines same/stats.csv 4
    "$EXE" record --input script:circles --trajectory same/stats.csv >log.txt 2>&1
    rc=$?
    cat log.txt
    [ "$rc" -eq 1 ] || { kill -INT "$first"; fail "record into the run's folder: exit status $rc"; }
    grep -q "error: another run is writing into same (process $first: " log.txt || fail "the run is not named"
    "$EXE" run --duration 0.1 "${SMALL[@]}" "${RENDER[@]}" --video "$OUT/show.mp4" --out other >log.txt 2>&1
    rc=$?
    cat log.txt
    kill -INT "$first"
    wait "$first"
    [ "$rc" -eq 1 ] || fail "a second run onto the first's video: exit status $rc"
    grep -qF "error: --video: another process is writing $OUT/show.mp4 (it holds $OUT/show.mp4.partial)" log.txt ||
      fail "the video's writer is not named"
    [ ! -e other/stats.json ] || fail "the refused run wrote stats.json"
    awk -F, 'NR > 1 && NF != 22 { bad = 1 } END { exit bad }' same/stats.csv || fail "stats.csv has rows cut or mixed"
    [ "$(mp4_frames show.mp4)" -gt 0 ] || fail "the first run's video does not play"
    ;;
  inputs_that_are_no_files)
    # A FIFO, a device or a folder where an input file should be is named before anything could wait on it.
    mkfifo fifo.bin fifo.png
    mkdir folder.bin
    for forest in /dev/zero fifo.bin folder.bin; do
      timeout 20 "$EXE" evaluate missing.tar.gz --forest $forest >log.txt 2>&1
      rc=$?
      [ "$rc" -eq 1 ] || fail "--forest $forest: exit status $rc (124: it blocked or read for ever)"
      grep -q "error: hand forest model $forest is a" log.txt || fail "--forest $forest: $(cat log.txt)"
      echo "--forest $forest: $(cat log.txt)"
    done
    timeout 60 "$EXE" run --duration 0.1 "${SMALL[@]}" "${RENDER[@]}" --environment fifo.png --out run >log.txt 2>&1
    rc=$?
    [ "$rc" -eq 1 ] || fail "--environment on a FIFO: exit status $rc (124: it blocked)"
    grep -q "PNG fifo.png is a FIFO" log.txt || fail "--environment on a FIFO: $(cat log.txt)"
    ;;
  experiment_killed)
    # An experiment says "running" in experiment.json while it runs: one killed outright leaves that, not the
    # previous "finished"; SIGHUP (a closed terminal) stops it as SIGTERM does.
    mkdir run
    echo '{"experiment": "minimal-surface", "status": "finished"}' >run/experiment.json
    for signal in KILL HUP; do
      "$EXE" run --scene minimal-surface --particles 50000 --out run >log.txt 2>&1 &
      pid=$!
      wait_for_text log.txt "experiment minimal-surface"
      kill -$signal "$pid"
      wait "$pid"
      rc=$?
      cat log.txt run/experiment.json
      if [ $signal = KILL ]; then
        grep -q '"status": "running"' run/experiment.json ||
          fail "SIGKILL left experiment.json $(cat run/experiment.json)"
      else
        [ "$rc" -eq 129 ] || fail "the experiment after SIGHUP: exit status $rc, expected 129"
        grep -q '"status": "interrupted"' run/experiment.json || fail "SIGHUP: experiment.json does not say interrupted"
      fi
    done
    ;;
  record_exit_status)
    # record on a camera records until Ctrl-C or SIGTERM, writes what it recorded and exits 130 or 143 as the
    # exit table says.
    "$MAKE_RECORDING" frame 1 >/dev/null || fail "could not write the synthetic depth frame"
    GB_FAKE_KINECT_FRAME=$(ls frame/d-*.pgm)
    export GB_FAKE_KINECT_FRAME GIANTBUBBLE_FREENECT_LIBRARY=$FAKE
    for signal in INT:130 TERM:143; do
      "$EXE" record --input kinect --trajectory k.csv >log.txt 2>&1 &
      pid=$!
      wait_for_text log.txt "frames, left hand"  # its progress, once a second on stderr
      sleep 1
      kill -"${signal%:*}" "$pid"
      wait "$pid"
      rc=$?
      cat log.txt
      [ "$rc" -eq "${signal#*:}" ] || fail "record after SIG${signal%:*}: exit status $rc, expected ${signal#*:}"
      grep -q "trajectory written to k.csv" log.txt || fail "the recording was not written"
      [ "$(wc -l <k.csv)" -gt 3 ] || fail "k.csv holds no rows"
    done
    ;;
  live_exit_status)
    # live ends on Ctrl-C or SIGTERM as Esc ends it, and exits 130 or 143 as the exit table says; it refuses
    # --render and --video by name rather than take them and write nothing, and names an --environment that is a
    # FIFO rather than wait on it.
    for signal in INT:130 TERM:143; do
      rm -f status.txt log.txt
      xvfb-run -a sh -c '"$@" >log.txt 2>&1 & echo $! >pid.txt; wait $!; echo $? >status.txt' sh \
        "$EXE" live --input script:circles --width 160 --height 120 --particles 400 --backend cpu &
      runner=$!
      wait_for_text log.txt "live: input"
      kill -"${signal%:*}" "$(cat pid.txt)"
      wait "$runner"
      cat log.txt
      [ "$(cat status.txt)" -eq "${signal#*:}" ] ||
        fail "live after SIG${signal%:*}: exit status $(cat status.txt), expected ${signal#*:}"
      grep -q "live: presented" log.txt || fail "the show's totals were not printed"
    done
    for args in "--render" "--video show.mp4" "--render-every 5" "--video-fps 25"; do
      # shellcheck disable=SC2086
      "$EXE" live $args >log.txt 2>&1 && fail "live $args exited 0"
      grep -q "live draws the show in its window and writes no files" log.txt || fail "live $args: $(cat log.txt)"
    done
    mkfifo sky.png
    timeout 60 xvfb-run -a "$EXE" live --frames 5 --width 160 --height 120 --particles 400 --backend cpu \
      --environment sky.png >log.txt 2>&1
    rc=$?
    cat log.txt
    [ "$rc" -ne 124 ] || fail "live blocked on an --environment FIFO"
    grep -q "PNG sky.png is a FIFO" log.txt || fail "the FIFO is not named"
    ;;
  numbers_and_empty_values)
    # Every number is decimal, finite and in range (no hex, no octal); a whole number may be written in any decimal
    # form; an option given '' is refused, not taken as left out.
    expect_refused "'0x10' is not a number (written in decimal)" run --width 0x10
    expect_refused "'0x1p-3' is not a number (written in decimal)" run --duration 0x1p-3
    expect_refused "'0x100' is not a number (written in decimal)" run --particles 0x100
    expect_refused "'6.5' is not a whole number" run --ply-every 6.5
    expect_refused "'0x10' is not a number (written in decimal)" bench --steps 0x10
    expect_refused "'0x10' is not a number (written in decimal)" live --frames 0x10
    expect_refused "'0x10' is not a number (written in decimal)" record --input script:circles --seed 0x10 --report
    expect_refused "parameter frameTime: '0x1p-6' is not a number (written in decimal)" run --param frameTime=0x1p-6
    expect_refused "'nan' is not a finite number" evaluate missing.tar.gz --depth-band nan 4
    expect_refused "'-1' is not in [0.3 - 10]" evaluate missing.tar.gz --depth-band -1 4
    expect_refused "--performer: expected X,Y,Z in metres with Z > 0, or auto; got '1,2'" run --performer 1,2
    expect_refused "--performer: expected X,Y,Z" run --performer 0x1,0,2
    for option in --scene --input --osc; do expect_refused "$option: an empty value" run $option ''; done
    expect_refused "--json: an empty value" bench --json ''
    expect_refused "the port must be a number from 1 to 65535" live --stream udp://127.0.0.1:99999
    # Whole numbers written as decimals with a point or an exponent are taken (as in a scene), "010" is ten.
    "$EXE" run --duration 0.04 --particles 4e2 --ply-every 010 --images-every 0 --backend cpu --no-render \
      --no-progress --out run >log.txt 2>&1 || fail "whole numbers in decimal forms: $(cat log.txt)"
    grep -q "giantbubble run: 400 particles" log.txt || fail "--particles 4e2 is not 400: $(cat log.txt)"
    ;;
  scene_keys_and_numbers)
    # An experiment's scene refuses the keys it would ignore; scene numbers take the forms the command line takes and
    # are named as written.
    printf 'name = "e"\nexperiment = "catenoid"\nduration = 2.0\n' >experiment.toml
    "$EXE" run --scene ./experiment.toml --out run >log.txt 2>&1 && fail "an experiment's duration was taken"
    grep -q "experiment.toml:3:1: 'duration' does not apply to the physics experiment 'catenoid'" log.txt ||
      fail "the key is not named: $(cat log.txt)"
    printf '%s\n' 'name = "s"' 'duration = 0.04' 'burst_at = -2' '[output]' 'ply_every = 0.0' 'images_every = 0' \
      '[params]' 'particlesAtFullSolution = 4e2' >whole.toml
    "$EXE" run --scene ./whole.toml --backend cpu --no-render --no-progress --out run >log.txt 2>&1 ||
      fail "whole numbers as TOML floats, burst_at = -2: $(cat log.txt)"
    printf 'name = "s"\nduration = 3600.0000001\n' >long.toml
    "$EXE" run --scene ./long.toml --out run >log.txt 2>&1 && fail "duration = 3600.0000001 was taken"
    grep -q "duration = 3600.0000001 is out of range \[0.001, 3600\]" log.txt || fail "$(cat log.txt)"
    printf 'name = "s"\n[render]\ncamera = [1e300, 1, 2]\n' >far.toml
    "$EXE" run --scene ./far.toml --out run >log.txt 2>&1 && fail "a camera 1e300 m away was taken"
    grep -q "camera in \[render\]: 1e+300 is not a coordinate" log.txt || fail "$(cat log.txt)"
    [ "$(wc -c <log.txt)" -lt 300 ] || fail "the number was printed whole: $(cat log.txt)"
    printf 'name = "s"\n[input]\nsource = "trajectory:../../../etc/passwd"\n' >outside.toml
    "$EXE" run --scene ./outside.toml --out run >log.txt 2>&1 && fail "a scene read a file outside its folder"
    grep -q "leaves the scene's folder" log.txt || fail "$(cat log.txt)"
    ;;
  messages_name_the_file_and_reason)
    # An --out path too long for the file system and a dangling symbolic link are named with the OS's reason; a
    # report on hands held still says there was no jitter to reduce instead of "-nanx"; an evaluation that matched
    # no hand prints no median.
    "$EXE" run --duration 0.04 "${SMALL[@]}" --out "$(printf 'a%.0s' $(seq 300))" >log.txt 2>&1 && fail "exited 0"
    grep -q "error: --out: cannot write a*: File name too long" log.txt || fail "ENAMETOOLONG: $(cat log.txt)"
    ln -s nowhere/deep dangling
    "$EXE" run --duration 0.04 "${SMALL[@]}" --out dangling >log.txt 2>&1 && fail "exited 0"
    grep -q "error: --out: dangling is a symbolic link to nowhere/deep, which does not exist" log.txt ||
      fail "the dangling link: $(cat log.txt)"
    trajectory $(seq 0 0.05 2) >still.csv
    "$EXE" record --input trajectory:still.csv --report >log.txt 2>&1 || fail "$(cat log.txt)"
    cat log.txt
    grep -qi "nan" log.txt && fail "the report holds a NaN"
    grep -Eq "^bspline +[0-9.]+ +[0-9.]+ +- " log.txt || fail "no '-' for the reduction of no jitter"
    "$MAKE_RECORDING" rec 10 >/dev/null || fail "could not write the synthetic recording"
    trajectory $(seq 0 1 9) | sed 's/-0.15,0,2,0.15,0,2$/-1.5,1,3.9,1.5,1,3.9/' >rec/hands.csv
    "$EXE" evaluate rec --each >log.txt 2>&1 || fail "$(cat log.txt)"
    cat log.txt
    grep -Eq "^rec +10 +0.0% +0.0% .* - +[0-9.]+$" log.txt || fail "a median of no matched hand was printed"
    ;;
  wands_rows_after_unstable)
    # A run that becomes unstable keeps one row per simulated frame in both row files.
    "$EXE" run --duration 1 "${SMALL[@]}" --param integrator=0 --param airPressureGain=10000 \
      --param pressureCoefficient=10000000 --param stabilitySafety=1 --out run >log.txt 2>&1
    rc=$?
    [ "$rc" -eq 3 ] || fail "exit status $rc, expected 3 (unstable): $(cat log.txt)"
    [ "$(wc -l <run/stats.csv)" -eq "$(wc -l <run/wands.csv)" ] ||
      fail "stats.csv has $(wc -l <run/stats.csv) lines, wands.csv $(wc -l <run/wands.csv)"
    ;;
  terminal_escapes_in_names)
    # An unknown scene's name and an --out path are printed escaped: an OSC sequence would set the terminal's title.
    "$EXE" run --scene "$(printf '\033]0;pwned\007')" >log.txt 2>&1 && fail "an unknown scene was taken"
    grep -qF "unknown scene '\x1b]0;pwned\x07'" log.txt || fail "the name is not escaped: $(cat -v log.txt)"
    "$EXE" run --duration 0.04 "${SMALL[@]}" --out "$(printf 'show\033[2J')" >log.txt 2>&1 || fail "$(cat -v log.txt)"
    grep -qF 'show\x1b[2J' log.txt || fail "the --out path is not named escaped: $(cat -v log.txt)"
    grep -q "$(printf '\033')" log.txt && fail "an escape sequence reached the terminal"
    ;;
  *) fail "unknown case $CASE" ;;
esac
echo "PASS: $CASE"
