#!/usr/bin/env bash
# giantbubble live with the Kinect unplugged mid-show and plugged back in, through the stand-in for
# the live libfreenect (fake_freenect.cpp), under Xvfb:
#   cli_kinect_reopen_test.sh EXE FAKE_LIBRARY MAKE_RECORDING OUT
# The show must notice the lost camera, keep going while it is away (reopening fails: no Kinect on the bus),
# and follow it again once it is back. Prints what it checks and exits non-zero with the reason otherwise.
set -u
source "$(dirname "$0")/live_show_on_fake_kinect.sh"

show_the_kinect_one_frame frame
export GB_FAKE_KINECT_UNPLUGGED_IF=$OUT/unplugged

start_live_show_on_fake_kinect

wait_for "note: calibration: performer at" || fail "the show did not start on the fake Kinect"
echo "the show started: $(grep -m1 "calibration: performer at" log.txt)"
sleep 1
touch unplugged
wait_for "the input has ended or was lost" || fail "the unplugged camera was not noticed"
echo "unplugged: $(grep -m1 'input lost' log.txt)"
sleep 3  # at least one attempt to reopen it fails while it is away
kill -0 "$group" 2>/dev/null || fail "the show stopped while the camera was away"
rm unplugged
wait_for "the camera is back" || fail "the camera was not followed again after it came back"
echo "plugged back: $(grep -m1 'the camera is back' log.txt)"
sleep 1
kill -0 "$group" 2>/dev/null || fail "the show stopped after the camera came back"
kill -TERM -- "-$group"
wait "$group" 2>/dev/null
echo "PASS"
