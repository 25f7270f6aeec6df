# Sourced by the live-window tests that run giantbubble live on the stand-in for the live libfreenect
# (fake_freenect.cpp) under Xvfb. Needs EXE, FAKE and the environment the stand-in reads (GB_FAKE_KINECT_*); the
# working directory gets log.txt.

fail() {
  echo "FAIL: $*"
  cat log.txt
  [ -n "${group:-}" ] && kill -TERM -- "-$group" 2>/dev/null
  exit 1
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
