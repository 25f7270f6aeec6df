#!/usr/bin/env bash
# giantbubble live while nobody stands before the Kinect, through the stand-in for the live libfreenect
# (fake_freenect.cpp), under Xvfb:
#   cli_live_waiting_test.sh EXE FAKE_LIBRARY MAKE_RECORDING OUT
# The show waits for a performer, and while it waits its window must stay alive: redrawn with the wait's message,
# and ended by a signal (as by Esc) with a word, not frozen. Prints what it checks and exits non-zero with the
# reason otherwise.
set -u
source "$(dirname "$0")/live_show_on_fake_kinect.sh"

# The empty room: the performer walks in only after 100 s.
show_the_kinect_one_frame room --nobody-until 100

start_live_show_on_fake_kinect

wait_for "waiting for a performer" || fail "the show did not say it waits for a performer"
echo "waiting: $(grep -m1 "waiting for a performer" log.txt)"
sleep 3  # 3 s at one redraw per 0.2 s: about 15 redraws
# SIGTERM to the show alone (as Esc would end it): the X server must outlive it for it to end cleanly.
show=$(pgrep -g "$group" -x "$(basename "$EXE")") || fail "no show process in the group"
kill -TERM "$show"
for _ in $(seq 300); do
  kill -0 "$show" 2>/dev/null || break
  sleep 0.1
done
kill -0 "$show" 2>/dev/null && fail "the show did not end within 30 s of SIGTERM while waiting"
wait "$group" 2>/dev/null
line=$(grep -m1 "ended while waiting for a performer" log.txt) || fail "the show did not say it ended while waiting"
echo "ended: $line"
redrawn=$(echo "$line" | sed -n 's/.*redrawn \([0-9]*\) times.*/\1/p')
# At least 5 redraws in 3 s (15 expected): the window lived through the wait. Lavapipe under load can be slow.
[ "${redrawn:-0}" -ge 5 ] || fail "the window was redrawn ${redrawn:-0} times in 3 s of waiting (at least 5 expected)"
echo "PASS"
