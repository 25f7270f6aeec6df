#!/usr/bin/env bash
# giantbubble live as a show runs it, one case per call, under Xvfb:
#   cli_live_show_test.sh EXE FAKE_LIBRARY MAKE_RECORDING OUT CASE
# Prints what it checks, then "PASS: CASE", or "FAIL: ..." with the log.
#   loop               the default performance plays again once the stage is empty, and blows a second bubble
#   fakenect_reset     R on a fakenect recording plays it again (fakenect plays one recording at a time)
set -u
source "$(dirname "$0")/live_show_on_fake_kinect.sh"  # EXE FAKE MAKE_RECORDING OUT, a fresh OUT, fail
CASE=$5
small=(--width 160 --height 120 --particles 600 --backend cpu)
# A UDP port for this test: one of 20,000, so that two tests running at once hardly ever pick the same.
free_port() { echo $((20000 + RANDOM % 20000)); }

case "$CASE" in
  loop)
    # One simulated frame per presented frame: the default performance's bubble is gone after about 4.5 s (225
    # frames); the stage stays empty for --auto-dip, the wands (back at the start since the bubble flew free) dip,
    # and the second bubble pinches off about 1.9 s later: 420 frames hold both with a second to spare.
    port=$(free_port)
    timeout 200 oscdump -L "$port" >osc.txt 2>&1 &
    dump=$!
    sleep 0.5
    timeout 240 xvfb-run -a "$EXE" live "${small[@]}" --fixed-step --auto-dip 0.5 --frames 420 \
      --osc "127.0.0.1:$port" >log.txt 2>&1
    rc=$?
    sleep 0.5
    kill "$dump" 2>/dev/null
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    grep -q "the performance is over: the wands go back to its start" log.txt || fail "the wands did not go back"
    grep -q "loop: new film, the performance from its start" log.txt || fail "no new film once the stage was empty"
    grep -q "played again [1-9]" log.txt || fail "the loop is not counted"
    pinched=$(grep -c '"pinched_off"' osc.txt)
    echo "pinch-offs: $pinched; $(grep 'a film was on stage' log.txt)"
    [ "$pinched" -ge 2 ] || fail "the second performance blew no second bubble ($pinched pinch-offs)"
    ;;
  fakenect_reset)
    "$MAKE_RECORDING" rec 60 >/dev/null || fail "could not write the synthetic recording"
    timeout 240 xvfb-run -a "$EXE" live --input fakenect:rec "${small[@]}" --fixed-step --keys 20:r 40:r \
      --frames 60 >log.txt 2>&1
    rc=$?
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    grep -q "another recording is already playing" log.txt && fail "R could not play the recording again"
    [ "$(grep -c 'reset: new film, performance from its start' log.txt)" -eq 2 ] || fail "two resets expected"
    grep -q "presented 60 frames" log.txt || fail "the show did not go on"
    ;;
  *) fail "unknown case $CASE" ;;
esac
echo "PASS: $CASE"
