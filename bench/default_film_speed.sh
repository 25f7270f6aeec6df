#!/bin/bash
# The default film's speed against real time, simulation only: the README's main job without rendering or outputs,
# run quiet and beside one busy process (a shell loop on one core), each condition the same number of times. The
# target is twice real time in both (docs/performance.md). The runs alternate quiet and busy, so that a drift of
# the machine's speed, which on a shared 2-core machine can reach a quarter within minutes, touches both alike.
#
# Prints each run's simulation frames/s (the run's "Avg. Time (fps) (simulation)": frames with a film on stage over
# their compute time) and its real-time factor (frames/s x the 0.02 s frame), then each condition's least and median.
#
# Usage: bench/default_film_speed.sh [runs per condition, default 3] [giantbubble binary, default build/app/giantbubble]
set -euo pipefail

runs=${1:-3}
binary=$(realpath "${2:-build/app/giantbubble}")
readonly kFrameSeconds=0.02 kTarget=2.0
if ! [[ $runs =~ ^[1-9][0-9]?$ ]]; then
  echo "default_film_speed: the number of runs must be 1 to 99, not '$runs'" >&2
  exit 2
fi
if [[ ! -x $binary ]]; then
  echo "default_film_speed: no giantbubble binary at $binary (build it first: cmake --build build)" >&2
  exit 2
fi

scratch=$(mktemp -d)
busy=
cleanup() {
  [[ -n $busy ]] && kill "$busy" 2>/dev/null
  rm -rf "$scratch"
}
trap cleanup EXIT

# One run in the scratch folder; prints its simulation frames/s.
film_fps() {
  local fps
  fps=$(cd "$scratch" && "$binary" run --no-render --no-progress --ply-every 0 --images-every 0 --out "$scratch/out" |
    awk '$1 == "default" { print $NF }')
  if [[ -z $fps ]]; then
    echo "default_film_speed: the run printed no frames/s line" >&2
    exit 1
  fi
  echo "$fps"
}

# A line of the table: run, condition, frames/s and real-time factor.
print_run() {
  printf '%-4s %-9s %9s %12.2f\n' "$1" "$2" "$3" "$(awk -v f="$3" -v t="$kFrameSeconds" 'BEGIN { print f * t }')"
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) cores"
printf '%-4s %-9s %9s %12s\n' run condition frames/s "x real time"
quiet=() loaded=()
for ((r = 1; r <= runs; ++r)); do
  fps=$(film_fps)
  quiet+=("$fps")
  print_run "$r" quiet "$fps"
  bash -c 'while :; do :; done' &
  busy=$!
  sleep 0.3 # the loop is on its core before the run starts
  fps=$(film_fps)
  kill "$busy"
  wait "$busy" 2>/dev/null || true
  busy=
  loaded+=("$fps")
  print_run "$r" busy "$fps"
done

# Least and median real-time factor of a condition's frames/s, and whether the median meets the target.
summarise() {
  local name=$1
  shift
  printf '%s\n' "$@" | sort -g | awk -v name="$name" -v frame="$kFrameSeconds" -v target="$kTarget" '
    { fps[NR] = $1 }
    END {
      median = NR % 2 ? fps[(NR + 1) / 2] : (fps[NR / 2] + fps[NR / 2 + 1]) / 2
      printf "%-6s least x%.2f, median x%.2f (target x%.2f: %s)\n", name, fps[1] * frame, median * frame, target,
             (median * frame >= target ? "met" : "missed")
    }'
}
summarise quiet "${quiet[@]}"
summarise busy "${loaded[@]}"
