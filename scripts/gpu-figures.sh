#!/usr/bin/env bash
# The Vulkan backend's figures on a machine with a GPU (docs/performance.md, the GPU rows): whole frames of the
# default film with 2 CPU threads and with all of them, 100,000 and 1,000,000 particles with 2 threads, the state
# read back, the README's main job rendered (how much its step and render overlap), and the default performance on
# the wall clock at 1920x1080 with a 100,000-particle film (and the render phase of its first 3 s with the follow
# camera and with a fixed one); then, where
# the tests are built, the Vulkan tests on that GPU. Each command has a time limit, and its summary lines are printed
# as it finishes, so that a run cut short still leaves figures; where the benchmarks are built, the step's GPU time by
# stage and the follow camera's framing. Needs a Release build in build/ (cmake -S . -B build && cmake --build build -j).
#   bash scripts/gpu-figures.sh [seconds per command, default 120]
set -u
limit=${1:-120}
exe=build/app/giantbubble
[ -x "$exe" ] || { echo "gpu-figures: no $exe: build first" >&2; exit 2; }
out=$(mktemp -d)
# The median of stats.csv's frame_ms (each frame's step, rules between steps and contact search; the statistics
# apart): the steady rate, without the first frames' one-off costs and the frames with a topology event that a short
# run's mean holds.
median_frame() {
  [ -f "$1" ] || return 0
  awk -F, 'NR == 1 { for (c = 1; c <= NF; ++c) if ($c == "frame_ms") col = c; next } $1 > 0 { print $col }' "$1" |
    sort -g | awk '{ v[NR] = $1 } END { if (NR) { m = v[int((NR + 1) / 2)]; printf "median frame_ms %.2f (%.0f frames/s)\n", m, 1000 / m } }'
}
run() {  # a label, the thread count, then the run's arguments
  local label=$1 threads=$2
  shift 2
  echo "== $label (OMP_NUM_THREADS=$threads)"
  rm -rf "$out/run"
  OMP_NUM_THREADS=$threads timeout "$limit" "$exe" run --backend vulkan --no-progress --ply-every 0 \
    --images-every 0 --out "$out/run" "$@" 2>&1 |
    grep -E "^backend|wall time|real-time factor|read back|frames held|ms per frame|overlap|^default|timed out" ||
    echo "(no summary)"
  median_frame "$out/run/stats.csv"
}
nproc=$(nproc)
run "default film, whole frames" 2 --no-render
run "default film, whole frames" "$nproc" --no-render
run "100,000 particles, whole frames" 2 --particles 100000 --duration 1 --no-render
run "1,000,000 particles, whole frames" 2 --particles 1000000 --duration 0.6 --no-render
run "1,000,000 particles, the work between steps on the CPU" 2 --particles 1000000 --duration 0.2 --no-render \
  --between-steps cpu
run "on the wall clock at 1920x1080, 100,000 particles" 2 --particles 100000 --realtime --render --width 1920 \
  --height 1080 --video ''
# The README's main job on the device: each frame drawn (960x540, MP4) while the next is stepped.
run "the main job, rendered at 960x540 with its MP4" 2
# Where that run's render phase goes: the follow camera's framing against the scene's fixed camera, no PNG written.
for camera in follow fixed; do
  run "1920x1080, 100,000 particles, the first 3 s, camera $camera, no PNG" 2 --particles 100000 --duration 3 \
    --render --width 1920 --height 1080 --video '' --render-every 0 --camera "$camera"
done
rm -rf "$out"
stages=build/bench/gb_stage_bench
if [ -x "$stages" ]; then
  echo "== the step's GPU time by stage (us a substep), 10,000 and 100,000 particles"
  OMP_NUM_THREADS=2 timeout "$limit" "$stages" --benchmark_filter='BM_VulkanStages/(10000|100000)/' 2>&1 |
    grep -E "^BM_|timed out" || echo "(no summary)"
fi
render=build/bench/gb_render_bench
if [ -x "$render" ]; then
  echo "== the follow camera's framing, CPU time a frame (2 threads)"
  OMP_NUM_THREADS=2 timeout "$limit" "$render" --benchmark_filter='BM_FollowCamera' 2>&1 |
    grep -E "^BM_|timed out" || echo "(no summary)"
fi
tests=build/tests/gb_tests
if [ -x "$tests" ]; then
  echo "== the Vulkan tests on this GPU"
  CI=true timeout "$limit" "$tests" --gtest_filter='VulkanEquivalence.*:VulkanReadback.*:DeviceContacts.*:DeviceStatistics.*:DeviceFilmChecks.*:Scenes/*:Renderer.*:RenderOutput.*:ThinFilm.*:FilmChecks.*' 2>&1 |
    grep -E "^\[  (PASSED|FAILED) |against the reference|timed out" || echo "(no summary)"
fi
