#!/usr/bin/env bash
# Soak test of a live show: `giantbubble live` under Xvfb with the scripted circles gesture looping
# for ever (the input is re-read at each reset), a burst every BURST_EVERY frames and --auto-dip 0.5, for
# MINUTES minutes (default 30). Samples the process's resident memory every minute and prints frames, dips,
# bursts and RSS at the start and the end; exits non-zero if the show ended on its own or memory grew by more
# than 10%. Extra arguments go to giantbubble live (e.g. --backend vulkan --particles 2000).
#   bash scripts/soak.sh [MINUTES] [live arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-30}
shift || true
exe=${GIANTBUBBLE:-./build/app/giantbubble}
log=$(mktemp /tmp/giantbubble_soak.XXXXXX)
burst_every=150  # frames: a burst, the film gone, and 0.5 s later a new dip
reset_every=3000 # frames: R re-reads the input from its start, so the scripted performance never ends

# Enough scripted keys for the whole soak at up to 60 frames/s; --frames ends it after MINUTES at that rate at
# most, and the time limit below ends it first at any lower rate.
max_frames=$((minutes * 60 * 60))
keys=()
for ((f = burst_every; f < max_frames; f += burst_every)); do keys+=("$f:b"); done
for ((f = reset_every; f < max_frames; f += reset_every)); do keys+=("$f:r"); done

xvfb-run -a "$exe" live --input script:circles --auto-dip 0.5 --width 320 --height 240 --particles 800 \
  --frames "$max_frames" --keys "${keys[@]}" "$@" >"$log" 2>&1 &
runner=$!
sleep 20  # the window, the device and the first film
pid=$(pgrep -n -f "$exe live --input script:circles")
rss() { awk '/VmRSS/ {print $2}' "/proc/$pid/status"; }
rss_start=$(rss)
echo "soak: pid $pid, RSS at start ${rss_start} kB"
for ((m = 1; m <= minutes; m++)); do
  sleep 60
  kill -0 "$pid" 2>/dev/null || {
    echo "soak: FAILED: the show ended on its own after $m minutes"
    tail -20 "$log"
    exit 1
  }
  echo "soak: minute $m, RSS $(rss) kB, last event: $(grep 'live: frame' "$log" | tail -1)"
done
rss_end=$(rss)
kill -INT "$pid" # as Ctrl-C: the show ends cleanly and prints its totals
wait "$runner" || true
bursts=$(grep -c ": burst$" "$log" || true)
echo "soak: $minutes min, $bursts bursts; $(grep 'live: presented' "$log")"
echo "soak: RSS ${rss_start} kB at start, ${rss_end} kB at the end"
awk -v a="$rss_start" -v b="$rss_end" 'BEGIN { exit !(b <= 1.1 * a) }' || {
  echo "soak: FAILED: memory grew by more than 10%"
  exit 1
}
echo "soak: passed (log: $log)"
