#!/usr/bin/env bash
# giantbubble live as a show runs it, one case per call, under Xvfb:
#   cli_live_show_test.sh EXE FAKE_LIBRARY MAKE_RECORDING OUT CASE
# Prints what it checks, then "PASS: CASE", or "FAIL: ..." with the log.
#   loop               the default performance plays again once the stage is empty, and blows a second bubble
#   fakenect_reset     R on a fakenect recording plays it again (fakenect plays one recording at a time)
#   osc_cues           cues over OSC dip, burst (burst_by_cue), pause and end the show; bad messages are counted
#   fullscreen         --fullscreen fills the screen at its resolution, F goes back to the window; a bad --monitor
#   stream             --stream udp://127.0.0.1:PORT is received by ffprobe as H.264 at the show's size
#   stream_unreachable a stream nobody can take (RTMP, nothing listening) is said once and the show goes on
#   performer_view     while the show waits for a performer on a camera, the performer view shows, and V hides it
#   operator_overlay   the show's messages are over the window with --operator, and never in the stream
set -u
source "$(dirname "$0")/live_show_on_fake_kinect.sh"  # EXE FAKE MAKE_RECORDING OUT, a fresh OUT, fail
CASE=$5
small=(--width 160 --height 120 --particles 600 --backend cpu)
# A UDP port for this test: one of 20,000, so that two tests running at once hardly ever pick the same.
free_port() { echo $((20000 + RANDOM % 20000)); }
# giantbubble live ARGS... under xvfb-run (with the options in the array screen, if any), its output in log.txt;
# returns the show's own exit status: xvfb-run's differs when it fails to clean up its temporary folder.
screen=()
live() {
  rm -f status.txt
  timeout 240 xvfb-run -a "${screen[@]}" sh -c '"$@" >log.txt 2>&1; echo $? >status.txt' sh "$EXE" live "$@"
  [ -s status.txt ] || return 99
  return "$(cat status.txt)"
}

case "$CASE" in
  loop)
    # One simulated frame per presented frame: the default performance's bubble is gone after about 4.5 s (225
    # frames); the stage stays empty for --auto-dip, the wands (back at the start since the bubble flew free) dip,
    # and the second bubble pinches off about 1.9 s later: 420 frames hold both with a second to spare.
    port=$(free_port)
    timeout 200 oscdump -L "$port" >osc.txt 2>&1 &
    dump=$!
    sleep 0.5
    live "${small[@]}" --fixed-step --auto-dip 0.5 --frames 420 --osc "127.0.0.1:$port"
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
    live --input fakenect:rec "${small[@]}" --fixed-step --keys 20:r 40:r --frames 60
    rc=$?
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    grep -q "another recording is already playing" log.txt && fail "R could not play the recording again"
    [ "$(grep -c 'reset: new film, performance from its start' log.txt)" -eq 2 ] || fail "two resets expected"
    grep -q "presented 60 frames" log.txt || fail "the show did not go on"
    ;;
  osc_cues)
    in=$(free_port)
    out=$(free_port)
    timeout 200 oscdump -L "$out" >osc.txt 2>&1 &
    dump=$!
    sleep 0.5
    live "${small[@]}" --osc-in "$in" --osc "127.0.0.1:$out" --auto-dip -1 --frames 100000000 &
    show=$!
    for _ in $(seq 600); do grep -q "taking OSC cues on UDP port $in" log.txt && grep -q "simulation on" log.txt && break; sleep 0.1; done
    grep -q "simulation on" log.txt || fail "the show did not start"
    cue() { oscsend 127.0.0.1 "$in" "$@" || fail "oscsend $*"; sleep 1; }
    cue /giantbubble/burst
    cue /giantbubble/pause i 1
    cue /giantbubble/pause i 0
    cue /giantbubble/dip f 0     # a push button let go of: no cue
    cue /giantbubble/explode     # unknown
    cue /giantbubble/burst s now # malformed
    printf 'not osc' >"/dev/udp/127.0.0.1/$in"  # malformed
    sleep 1
    cue /giantbubble/dip
    cue /giantbubble/quit
    wait "$show"
    rc=$?
    sleep 0.5
    kill "$dump" 2>/dev/null
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    for said in "cue burst: burst" "cue pause: paused" "cue pause: resumed" "cue dip: new film" \
      "cue quit: the show ends" "OSC cues: 6 taken, 1 unknown and 2 malformed ignored"; do
      grep -q "$said" log.txt || fail "not said: $said"
    done
    [ "$(grep -c 'cue dip' log.txt)" -eq 1 ] || fail "the dip let go of was taken as a cue"
    grep -q '"burst_by_cue"' osc.txt || fail "no burst_by_cue event went out"
    grep -q '/giantbubble/cue ssd "burst" "burst"' osc.txt || fail "the burst cue was not reported"
    grep -q '/joint sifff "l_hand" 1' osc.txt || fail "no hands went out as OSCeleton joints"
    echo "events out: $(grep -o '"burst_by_cue"\|/giantbubble/cue ssd "[a-z]*"' osc.txt | sort | uniq -c | tr '\n' ' ')"
    ;;
  fullscreen)
    # A monitor that is not there is named with the ones that are.
    screen=(-s "-screen 0 800x600x24")
    live "${small[@]}" --fullscreen --monitor 3 --frames 1
    [ $? -eq 1 ] || fail "--monitor 3 on one monitor was taken"
    grep -q "error: --monitor 3: the display has 1 monitor (0 '[^']*' 800x600)" log.txt || fail "the monitors not named"
    # Full screen on an 800x600 screen: the window covers it from its corner, and the picture is drawn at its size;
    # F (a key at frame 250) brings the 160x120 window back.
    cat >check.sh <<EOF
"$EXE" live ${small[*]} --fullscreen --fixed-step --frames 400 --keys 250:f >log.txt 2>&1 &
show=\$!
for _ in \$(seq 1200); do grep -q "simulation on" log.txt && break; sleep 0.1; done
sleep 2  # some frames shown, and far from frame 250 (the show runs at 15 to 50 frames/s here)
xwininfo -root -tree >tree.txt
wait \$show
echo "show exit \$?" >>log.txt
EOF
    timeout 240 xvfb-run -a -s "-screen 0 800x600x24" bash check.sh
    grep -q "show exit 0" log.txt || fail "the show failed"
    grep -q "full screen on monitor 0 '[^']*' 800x600 at 0,0, drawing at 800x600" log.txt || fail "not drawn at 800x600"
    window=$(grep '"giantbubble' tree.txt | head -1)
    echo "the window: $window"
    echo "$window" | grep -q " 800x600+0+0 " || fail "the window does not cover the 800x600 screen: $window"
    grep -q "frame 250: a window, drawing at 160x120" log.txt || fail "F did not go back to the window"
    ;;
  stream)
    port=$(free_port)
    # ffprobe waits (up to 60 s) for the stream on the loopback address and reports what it receives.
    timeout 120 ffprobe -v error -show_entries stream=codec_name,width,height -of default=nw=1 \
      "udp://127.0.0.1:$port?timeout=60000000" >probe.txt 2>&1 &
    probe=$!
    sleep 1
    live "${small[@]}" --stream "udp://127.0.0.1:$port" --frames 200
    rc=$?
    wait "$probe"
    echo "ffprobe: $(tr '\n' ' ' <probe.txt)"
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    grep -q "streaming 160x120 to udp://127.0.0.1:$port" log.txt || fail "the stream did not start"
    grep -q "codec_name=h264" probe.txt && grep -q "width=160" probe.txt && grep -q "height=120" probe.txt ||
      fail "ffprobe did not receive a 160x120 H.264 stream: $(cat probe.txt)"
    sent=$(sed -n 's/.*stream: \([0-9]*\) frames sent.*/\1/p' log.txt)
    echo "$(grep 'stream:' log.txt)"
    # At least half the 200 frames reach ffmpeg (the rest dropped while it is busy: it runs below the show).
    [ "${sent:-0}" -ge 100 ] || fail "only ${sent:-0} of 200 frames were sent"
    ;;
  stream_unreachable)
    live "${small[@]}" --stream rtmp://127.0.0.1:9/live/show --frames 150
    rc=$?
    [ "$rc" -eq 0 ] || fail "exit status $rc"
    grep -q "warning: stream: ffmpeg sending to rtmp://127.0.0.1:9/live/show ended" log.txt || fail "not said"
    grep -q "presented 150 frames" log.txt || fail "the show did not go on"
    "$EXE" live --stream http://example.com/x >log.txt 2>&1
    [ $? -eq 1 ] || fail "an http address was taken"
    grep -q "not an address to stream to" log.txt || fail "the address was not refused by name"
    ;;
  performer_view)
    # Nobody before the camera (the stand-in Kinect shows the empty room for ever): the show waits, and the
    # performer view shows what the camera sees; a V cue hides it; then a quit cue ends the show as Esc would.
    show_the_kinect_one_frame room --nobody-until 100
    export GIANTBUBBLE_FREENECT_LIBRARY=$FAKE
    in=$(free_port)
    live --input kinect "${small[@]}" --osc-in "$in" &
    show=$!
    for _ in $(seq 600); do grep -q "waiting for a performer" log.txt && break; sleep 0.1; done
    grep -q "the performer view shows what the camera sees" log.txt || fail "the performer view did not show"
    oscsend 127.0.0.1 "$in" /giantbubble/performer_view
    sleep 2
    oscsend 127.0.0.1 "$in" /giantbubble/quit
    wait "$show"
    grep -q "cue performer_view: performer view off" log.txt || fail "the V cue did not hide the view"
    grep -q "ended while waiting for a performer" log.txt || fail "the quit cue did not end the wait"
    ;;
  operator_overlay)
    # A recording's messages ("calibration: performer at ...", "input ended ...") go to the operator overlay for 5 s:
    # a dark banner over the window's top rows, while the streamed picture keeps the sky there on every frame.
    "$MAKE_RECORDING" rec 60 >/dev/null || fail "could not write the synthetic recording"
    port=$(free_port)
    # The receiver waits up to 10 s for the stream (a busy machine starts the show slowly) and ends 10 s after the
    # stream does (udp's timeout, in microseconds).
    timeout 120 ffmpeg -v error -y -i "udp://127.0.0.1:$port?timeout=10000000" -vf "crop=160:8:0:0,format=gray" \
      -f rawvideo stream_top.raw &
    receiver=$!
    sleep 1
    cat >check.sh <<SCRIPT
"$EXE" live --input fakenect:rec ${small[*]} --operator --stream udp://127.0.0.1:$port --frames 300 >log.txt 2>&1 &
show=\$!
for _ in \$(seq 1200); do grep -q "calibration: performer at" log.txt && break; sleep 0.1; done
sleep 1  # the message is on for 5 s: the window's picture now holds it
xwininfo -root -tree >tree.txt
ffmpeg -v error -y -f x11grab -video_size 800x600 -i "\$DISPLAY" -frames:v 1 -vf format=gray -f rawvideo screen.raw
wait \$show
echo "show exit \$?" >>log.txt
SCRIPT
    timeout 240 xvfb-run -a -s "-screen 0 800x600x24" bash check.sh
    wait "$receiver"
    grep -q "show exit 0" log.txt || fail "the show failed"
    # The window's corner on the screen (xwininfo), then the mean grey (0-255) of its rows 0-7 and of the stream's
    # on each frame: the banner is dark (under 60), the sky light (over 100).
    read -r x y < <(grep '"giantbubble' tree.txt | head -1 | sed -n 's/.* 160x120+\([0-9]*\)+\([0-9]*\) .*/\1 \2/p')
    [ -n "${x:-}" ] || fail "no 160x120 window on the screen: $(grep giantbubble tree.txt)"
    window_top=$(python3 -c "
d = open('screen.raw', 'rb').read()
print(int(sum(sum(d[(${y} + r) * 800 + ${x}:(${y} + r) * 800 + ${x} + 160]) for r in range(8)) / (8 * 160)))")
    read -r frames darkest < <(python3 -c "
d = open('stream_top.raw', 'rb').read(); n = 160 * 8
means = [sum(d[i:i + n]) / n for i in range(0, len(d) - n + 1, n)]
print(len(means), int(min(means)) if means else -1)")
    echo "window's top rows: grey $window_top; the stream's: $frames frames, the darkest grey $darkest"
    [ "$window_top" -lt 60 ] || fail "the operator overlay is not over the window (grey $window_top)"
    [ "$frames" -ge 50 ] || fail "only $frames stream frames received"
    [ "$darkest" -gt 100 ] || fail "the operator overlay is in the stream (grey $darkest)"
    ;;
  *) fail "unknown case $CASE" ;;
esac
echo "PASS: $CASE"
