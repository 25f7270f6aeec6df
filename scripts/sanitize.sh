#!/usr/bin/env bash
# The sanitizer run of issue 14: the whole project built with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer (GIANTBUBBLE_SANITIZE) and libFuzzer coverage (GIANTBUBBLE_FUZZ) in build-sanitize/,
# the whole test suite run under the sanitizers, then each parser's fuzzer run for FUZZ_SECONDS (default 300)
# on a copy of its corpus (tests/fuzz/corpus/NAME). Too slow for CI on two cores (docs/performance.md has the
# times); run it before a show and after changing a parser.
#   bash scripts/sanitize.sh [FUZZ_SECONDS] [ctest arguments, e.g. -R ShowProof]
set -euo pipefail
cd "$(dirname "$0")/.."
fuzz_seconds=${1:-300}
shift || true
build=build-sanitize

CXX=clang++ CC=clang cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGIANTBUBBLE_SANITIZE=ON \
  -DGIANTBUBBLE_FUZZ=ON -DGIANTBUBBLE_BUILD_BENCH=OFF
cmake --build "$build" -j"$(nproc)"

# detect_leaks=0: Mesa's lavapipe and the Vulkan loader keep allocations until exit, by design; every other
# check stays on. UBSan prints a stack and stops at the first error (-fno-sanitize-recover).
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
start=$(date +%s)
ctest --test-dir "$build" --output-on-failure -j2 --timeout 3000 "$@"
echo "sanitize: test suite under ASan + UBSan took $(($(date +%s) - start)) s"

[ "$fuzz_seconds" -gt 0 ] || exit 0
for name in scene trajectory fakenect; do
  work="$build/fuzz-corpus/$name"
  mkdir -p "$work"
  cp -n tests/fuzz/corpus/"$name"/* "$work"/
  echo "sanitize: fuzzing the $name parser for $fuzz_seconds s"
  "$build/tests/fuzz/fuzz_$name" -max_total_time="$fuzz_seconds" -max_len=4096 -timeout=10 -rss_limit_mb=4096 \
    -print_final_stats=1 "$work"
done
