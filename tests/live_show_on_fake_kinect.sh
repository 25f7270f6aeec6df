# Sourced by the live-window tests that run giantbubble live on the stand-in for the live libfreenect
# (fake_freenect.cpp) under Xvfb, with the arguments EXE FAKE_LIBRARY MAKE_RECORDING OUT: it takes them, and the
# test then works in a fresh OUT (log.txt, the depth frame).
EXE=$1
FAKE=$2
MAKE_RECORDING=$3
OUT=$4
rm -rf "$OUT"
mkdir -p "$OUT"
cd "$OUT" || exit 1

fail() {
  echo "FAIL: $*"
  cat log.txt
  [ -n "${group:-}" ] && kill -TERM -- "-$group" 2>/dev/null
  exit 1
}

# The one depth frame the stand-in Kinect shows for ever: make_synthetic_recording's first frame into NAME, with
# its further options (e.g. --nobody-until SECONDS).
show_the_kinect_one_frame() {
  local name=$1
  shift
  "$MAKE_RECORDING" "$name" 1 "$@" >/dev/null || fail "could not write the synthetic depth frame"
  GB_FAKE_KINECT_FRAME=$(ls "$name"/d-*.pgm)
  export GB_FAKE_KINECT_FRAME
}

# Starts the show in its own process group (so that it and Xvfb can be stopped as a whole); sets $group.
start_live_show_on_fake_kinect() {
  export GIANTBUBBLE_FREENECT_LIBRARY=$FAKE
  setsid xvfb-run -a "$EXE" live --input kinect --width 160 --height 120 --particles 400 --backend cpu \
    >log.txt 2>&1 &
  group=$!
}

# Waits (at most 120 s) for TEXT in the log while the show runs.
wait_for() {
  for _ in $(seq 1200); do
    grep -q "$1" log.txt && return 0
    kill -0 "$group" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}
