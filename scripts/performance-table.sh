#!/usr/bin/env bash
# The quick rows of docs/performance.md's tables, measured on this machine at the present commit and printed as rows
# of its table (figure | value | command | commit), to replace the rows of the machine's table where they stand:
#   - the default film, simulation only, quiet and beside one busy process (bench/default_film_speed.sh);
#   - the README's main job, its wall time;
#   - where the benchmarks are built (build/bench/): the film flow stage and the frame's statistics;
#   - with --gpu: the Vulkan stepper alone (giantbubble bench); scripts/gpu-figures.sh has the GPU's other rows.
# The other rows (live, the stress runs, the suite, the hands) take minutes to hours each: their commands are in the
# tables. Needs a Release build in build/ (cmake -S . -B build && cmake --build build -j2).
#   bash scripts/performance-table.sh [--gpu] [RUNS, default 3]
set -euo pipefail
cd "$(dirname "$0")/.."

gpu=0
if [[ ${1:-} == --gpu ]]; then
  gpu=1
  shift
fi
runs=${1:-3}
exe=$PWD/build/app/giantbubble
bench=$PWD/build/bench
[[ -x $exe ]] || { echo "performance-table: no $exe: build first" >&2; exit 2; }
commit=$(git rev-parse --short=7 HEAD)
[[ -z $(git status --porcelain --untracked-files=no) ]] || commit="$commit (with changes not committed)"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

row() {  # figure, value, command
  printf '| %s | %s | `%s` | `%s` |\n' "$1" "$2" "$3" "$commit"
}

# A Google Benchmark's rows as "name: time unit" (its label where it gives one), from its CSV.
benchmark_times() {
  "$@" --benchmark_format=csv 2>/dev/null | awk -F, '/^"BM_/ {
      gsub(/"/, "", $1); gsub(/"/, "", $8); sub(/\/real_time$/, "", $1)
      printf "%s%s: %.2f %s", sep, ($8 != "" ? $8 : $1), $3, $5; sep = "; "
    } END { print "" }'
}

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) cores" >&2

speed=$(bash bench/default_film_speed.sh "$runs" "$exe")
quiet=$(awk '$2 == "quiet" { printf "%s%s (x%s)", sep, $3, $4; sep = ", " }' <<<"$speed")
busy=$(awk '$2 == "busy" { printf "%s%s (x%s)", sep, $3, $4; sep = ", " }' <<<"$speed")
row "default film, simulation only (target: twice real time, x2.00, quiet and beside one busy process)" \
  "quiet $quiet frames/s; one busy process $busy" "bash bench/default_film_speed.sh $runs"

start=$(date +%s.%N)
(cd "$scratch" && "$exe" run --no-progress --out "$scratch/out" >/dev/null)
wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
row "the README's main job (rendered at 960x540, \`render.mp4\`)" "$wall s wall for its 6 s" "time giantbubble run"

if [[ -x $bench/gb_stage_bench ]]; then
  row "film flow stage and the paper's drainage, 10,000 particles" \
    "$(OMP_NUM_THREADS=2 benchmark_times "$bench/gb_stage_bench" --benchmark_filter='BM_CpuStage/10000/1[45]/')" \
    "OMP_NUM_THREADS=2 gb_stage_bench --benchmark_filter='BM_CpuStage/10000/1[45]/'"
fi
if [[ -x $bench/gb_statistics_bench ]]; then
  row "the frame's statistics (\`Simulation::stats\`), film hanging still" \
    "$(benchmark_times "$bench/gb_statistics_bench")" "gb_statistics_bench"
fi
if ((gpu)); then
  # A row of the bench's table: the backend's name in 44 columns, the particles, the steps/s, then the rest.
  steps=$("$exe" bench --sizes 10000 100000 1000000 --backends vulkan --steps 16 --json "$scratch/bench.json" |
    awk '/^vulkan/ { split(substr($0, 46), f, " "); printf "%s%s particles %s", sep, f[1], f[2]; sep = "; " }')
  row "Vulkan stepper alone, implicit steps/s" "$steps" \
    "giantbubble bench --sizes 10000 100000 1000000 --backends vulkan --steps 16"
fi
