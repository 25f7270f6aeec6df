#!/bin/bash
# The README's main job (`giantbubble run`: the default film rendered at 960x540, PNG and MP4) against the same scene
# simulated only (`run --no-render`), side by side, quiet and beside one busy process (a shell loop on one core). The
# runs alternate: simulation only, main job, each quiet then busy, so that a drift of a shared machine's speed touches
# all four alike. With --live, `live` at 960x540 (under xvfb-run) joins each round: its frames/s while a film is shown.
#
# Prints each run's wall time (the process, start to exit), the stepper's ms per frame (stats.json "phase_ms.step")
# and the render's ("phase_ms.render": the frame's submission, the wait for the frame two before it, its PNG and
# video); then each condition's medians and the ratios against the targets (docs/performance.md):
#   main job wall <= 2.0 x simulation-only wall;  step ms in the main job <= 1.3 x simulation only;
#   live frames/s while a film is shown >= 0.5 x the simulation-only frames/s.
#
# Usage: bench/main_job_speed.sh [rounds, default 3] [giantbubble binary, default build/app/giantbubble] [--live]
# MAIN_JOB_ARGS adds arguments to the main job's runs only, e.g. MAIN_JOB_ARGS="--render-scale 1" to draw at the full
# size on a CPU driver.
set -euo pipefail

rounds=${1:-3}
binary=$(realpath "${2:-build/app/giantbubble}")
live=${3:-}
read -r -a main_args <<<"${MAIN_JOB_ARGS:-}"
refuse() {
  echo "main_job_speed: $1" >&2
  exit 2
}
[[ $rounds =~ ^[1-9][0-9]?$ ]] || refuse "the number of rounds must be 1 to 99, not '$rounds'"
[[ -x $binary ]] || refuse "no giantbubble binary at $binary (build it first: cmake --build build)"
[[ -z $live || $live == --live ]] || refuse "the third argument is --live or nothing, not '$live'"

scratch=$(mktemp -d)
busy=
trap '[[ -n $busy ]] && kill "$busy" 2>/dev/null; rm -rf "$scratch"' EXIT

# One run of the default scene (extra arguments: --no-render for the simulation only); prints its wall s, step ms,
# render ms and simulation frames/s.
run_once() {
  local start end
  start=$(date +%s.%N)
  (cd "$scratch" && "$binary" run --no-progress --ply-every 0 --images-every 0 --out "$scratch/out" "$@" >"$scratch/log" 2>&1) || {
    echo "main_job_speed: the run failed:" >&2
    tail -5 "$scratch/log" >&2
    exit 1
  }
  end=$(date +%s.%N)
  jq -r --arg wall "$(awk -v s="$start" -v e="$end" 'BEGIN { print e - s }')" \
    '"\($wall) \(.phase_ms.step) \(.phase_ms.render) \(.average.frames_per_second)"' \
    "$scratch/out/stats.json"
}

# live at 960x540 for 600 frames; prints its frames/s while a film is shown.
live_once() {
  (cd "$scratch" && timeout 300 xvfb-run -a "$binary" live --frames 600 --width 960 --height 540 --backend cpu \
    >"$scratch/live" 2>&1) || true
  local fps
  fps=$(sed -n 's/.*while a film was shown: [0-9]* frames presented in [0-9.]* s (\([0-9.]*\) frames\/s).*/\1/p' \
    "$scratch/live")
  if [[ -z $fps ]]; then
    echo "main_job_speed: live printed no frames/s while a film was shown:" >&2
    tail -5 "$scratch/live" >&2
    exit 1
  fi
  echo "$fps"
}

start_busy() {
  bash -c 'while :; do :; done' &
  busy=$!
  sleep 0.3 # the loop is on its core before the run starts
}
stop_busy() {
  kill "$busy"
  wait "$busy" 2>/dev/null || true
  busy=
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) cores"
printf '%-5s %-6s %-9s %8s %8s %10s %9s\n' round load run "wall s" "step ms" "render ms" "live fps"
rows=()
for ((r = 1; r <= rounds; ++r)); do
  for load in quiet busy; do
    [[ $load == busy ]] && start_busy
    read -r wall step render fps <<<"$(run_once --no-render)"
    rows+=("$load sim $wall $step $render $fps -")
    printf '%-5s %-6s %-9s %8.2f %8.2f %10.2f %9s\n' "$r" "$load" sim-only "$wall" "$step" "$render" -
    read -r wall step render fps <<<"$(run_once "${main_args[@]+"${main_args[@]}"}")"
    lfps=-
    [[ -n $live ]] && lfps=$(live_once)
    rows+=("$load main $wall $step $render $fps $lfps")
    printf '%-5s %-6s %-9s %8.2f %8.2f %10.2f %9s\n' "$r" "$load" main-job "$wall" "$step" "$render" "$lfps"
    [[ $load == busy ]] && stop_busy
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

# Each condition's medians, their ratios and the targets.
printf '%s\n' "${rows[@]}" | awk '
  function median(list, n,   sorted, i, j, t) {
    for (i = 1; i <= n; ++i) sorted[i] = list[i]
    for (i = 2; i <= n; ++i) for (j = i; j > 1 && sorted[j - 1] > sorted[j]; --j) {
      t = sorted[j]; sorted[j] = sorted[j - 1]; sorted[j - 1] = t
    }
    return n % 2 ? sorted[(n + 1) / 2] : (sorted[n / 2] + sorted[n / 2 + 1]) / 2
  }
  function verdict(ok) { return ok ? "met" : "missed" }
  {
    key = $1 " " $2; n[key]++
    wall[key, n[key]] = $3; step[key, n[key]] = $4; fps[key, n[key]] = $6; live[key, n[key]] = $7
  }
  END {
    split("quiet busy", loads, " ")
    for (l = 1; l <= 2; ++l) {
      s = loads[l] " sim"; m = loads[l] " main"
      if (!n[s] || !n[m]) continue
      for (i = 1; i <= n[s]; ++i) { a[i] = wall[s, i]; b[i] = step[s, i]; c[i] = fps[s, i] }
      sw = median(a, n[s]); ss = median(b, n[s]); sf = median(c, n[s])
      for (i = 1; i <= n[m]; ++i) { a[i] = wall[m, i]; b[i] = step[m, i]; c[i] = live[m, i] }
      mw = median(a, n[m]); ms = median(b, n[m])
      printf "%-5s wall: main job %.2f s, simulation only %.2f s, x%.2f (target <= x2.0: %s)\n", loads[l], mw, sw,
             mw / sw, verdict(mw / sw <= 2.0)
      printf "%-5s step: main job %.2f ms, simulation only %.2f ms, x%.2f (target <= x1.3: %s)\n", loads[l], ms, ss,
             ms / ss, verdict(ms / ss <= 1.3)
      if (c[1] != "-") {
        lf = median(c, n[m])
        printf "%-5s live: %.1f frames/s while a film is shown, simulation only %.1f, x%.2f (target >= x0.5: %s)\n",
               loads[l], lf, sf, lf / sf, verdict(lf / sf >= 0.5)
      }
    }
  }'
